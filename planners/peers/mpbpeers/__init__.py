"""mpbpeers - other libraries' planners served through the Python kit.

One module per peer, named as the peer is on the wire and in
planner_configs.planner (ompl2, roboplan, mplib, ...), each with a class
Adapter that peer.py serves (peer.Peer, peer.main); run one with
`python -m mpbpeers.NAME` in its environment (planners/peers/mpb-planner-
peer does). The peers are the files of planners/peers/requirements/: a
peer is NAME.txt there and NAME.py here.
"""
