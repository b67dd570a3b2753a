"""test_kit.py - the Python kit (planners/python/mpbplanner) on its own,
with pytest: its authentication through libmpbench against the
protocol's test vector (tests/support/data/auth_vector.txt, which the C
library's tests/unit/net/test_auth.c reads too), its hub link's checks,
the robot text split it shares with libmpbench, and reading a request. Run by ctest as unit.python_kit
(tests/CMakeLists.txt), with the build's libmpbench and message types."""
import os
import socket
import time

import pytest
from mpb import goal_t, param_t, plan_request_t

from mpbplanner import request
from mpbplanner.limits import Limits
from mpbplanner.auth import TRAILER_BYTES, Auth, AuthError
from mpbplanner.hub import HubLCM, is_hub
from mpbplanner.world import World, split_robot_text

SOURCE = os.environ["MPB_SOURCE"]
DATA = os.path.join(SOURCE, "tests", "support", "data")


def _vector():
    out = {}
    with open(os.path.join(DATA, "auth_vector.txt")) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                key, _, value = line.rstrip("\n").partition(" ")
                out[key] = value
    return out


def test_auth_gives_the_protocol_test_vector(tmp_path):
    v = _vector()
    secret = tmp_path / "secret"
    secret.write_bytes(v["secret"].encode())
    auth = Auth(str(secret))
    message = bytes.fromhex(v["message"])
    trailer = auth.trailer(v["channel"], message, int(v["instance"], 16),
                           int(v["counter"]), int(v["echo"], 16))
    assert trailer.hex() == v["trailer"]
    # A receiver whose instance the vector's message echoes believes it
    # once; on another channel its tag is wrong.
    assert auth.open(v["channel"], message + trailer)[0] == Auth.UNPROVEN


def test_a_seal_is_this_process_instance_and_its_next_counter(tmp_path):
    secret = tmp_path / "secret"
    secret.write_bytes(b"the same secret, 32 bytes long..")
    auth = Auth(str(secret))
    assert auth.instance != 0
    for counter in (1, 2, 3):
        sealed = auth.seal("CH", b"hello", echo=0xfedcba9876543210)
        assert len(sealed) == 5 + TRAILER_BYTES
        assert sealed[:5] == b"hello"
        assert sealed[5:] == auth.trailer("CH", b"hello", auth.instance,
                                          counter, 0xfedcba9876543210)


def test_auth_believes_an_echo_and_refuses_a_replay(tmp_path):
    secret = tmp_path / "secret"
    secret.write_bytes(b"the same secret, 32 bytes long..")
    me, peer = Auth(str(secret)), Auth(str(secret))
    assert me.instance != peer.instance
    first = peer.seal("CH", b"hello", echo=0)
    assert me.open("CH", first) == (Auth.UNPROVEN, b"hello", peer.instance)
    answer = peer.seal("CH", b"hello", echo=me.instance)
    verdict, body, sender = me.open("CH", answer)
    assert (verdict, body, sender) == (Auth.FRESH, b"hello", peer.instance)
    assert me.open("CH", answer)[0] == Auth.REPLAYED
    assert me.open("OTHER", peer.seal("CH", b"x", me.instance)) == \
        (Auth.BAD_TAG, None, 0)
    assert me.open("CH", answer[:TRAILER_BYTES - 1]) == (Auth.BAD_TAG, None, 0)
    other = tmp_path / "other"
    other.write_bytes(b"another secret of 32 bytes......")
    assert me.open("CH", Auth(str(other)).seal("CH", b"x", me.instance))[0] \
        == Auth.BAD_TAG
    assert "replay" in Auth.verdict_text(Auth.REPLAYED)


def test_a_short_or_missing_secret_is_refused_naming_the_file(tmp_path):
    secret = tmp_path / "secret"
    secret.write_bytes(b"too short")
    with pytest.raises(AuthError, match=f"^{secret}: a secret needs at "
                       f"least 16 bytes, this has 9$"):
        Auth(str(secret))
    with pytest.raises(ValueError, match=f"^{tmp_path}/none: cannot read "
                       f"secret: No such file"):
        Auth(str(tmp_path / "none"))


def test_a_hub_url_is_told_and_checked_by_libmpbench():
    assert is_hub("tcpq://127.0.0.1:7700")
    assert is_hub("tcpq://")
    assert not is_hub("udpm://239.255.76.67:7667?ttl=0")
    assert not is_hub("")
    assert not is_hub(None)
    for bad in ("tcpq://h:0", "tcpq://h:65536", "tcpq://h:x1", "tcpq://h:"):
        with pytest.raises(ValueError, match="tcpq://HOST:PORT"):
            HubLCM(bad, ["CH"])


def test_a_hub_link_subscribes_only_what_it_told_the_hub():
    # A loopback port bound but not listening: every connection is
    # refused, and the link keeps trying.
    closed = socket.socket()
    closed.bind(("127.0.0.1", 0))
    link = HubLCM(f"tcpq://127.0.0.1:{closed.getsockname()[1]}", ["MPB_ACK_x"])
    try:
        with pytest.raises(ValueError, match="not given to the hub link"):
            link.subscribe("MPB_STATUS", lambda channel, data: None)
        link.subscribe("MPB_ACK_x", lambda channel, data: None)
        link.publish("MPB_ACK_x", b"lost while the hub is away")
        assert link.handle_timeout(0) == 0
        assert link.stats().is_hub == 1 and link.connects == 0
    finally:
        link.close()
        closed.close()


URDF = '<robot name="r">\n  <link name="a"/>\n</robot>\n'
SRDF = '<robot name="r">\n  <group name="g"/>\n</robot>\n'


@pytest.mark.parametrize("text, urdf, srdf", [
    (URDF, URDF, None),
    (URDF + SRDF, URDF, SRDF),
    # A "</robot>" in a comment is not the URDF's end.
    ('<robot name="r"><!-- </robot> -->\n</robot>\n' + SRDF,
     '<robot name="r"><!-- </robot> -->\n</robot>\n', SRDF),
    # Comments and blanks after the URDF are no SRDF.
    (URDF + "\n<!-- the end -->\n", URDF, None),
    # More on the line of the end tag: the SRDF begins right after it.
    ('<robot name="r"></robot >' + SRDF, '<robot name="r"></robot >', SRDF),
])
def test_the_robot_text_splits_where_libmpbench_splits_it(text, urdf, srdf):
    assert split_robot_text(text) == (urdf, srdf)


def _planar_world():
    with open(os.path.join(SOURCE, "scenes", "planar", "arm3.robot")) as f:
        robot = f.read()
    with open(os.path.join(SOURCE, "scenes", "planar", "pillars.scene")) as f:
        scene = f.read()
    return World("planar", robot, "planar", scene,
                 ["shoulder", "elbow", "wrist"])


def _request(goal_joints, params=()):
    req = plan_request_t()
    req.goal = goal_t()
    req.goal.kind = goal_t.JOINTS
    req.goal.num_joints = len(goal_joints)
    req.goal.joints = list(goal_joints)
    req.params = []
    for key, value in params:
        p = param_t()
        p.key, p.value = key, value
        req.params.append(p)
    req.num_params = len(req.params)
    return req


def test_a_joint_goal_is_its_own_goal_configuration():
    world = _planar_world()
    try:
        req = _request([0.1, 0.2, 0.3])
        assert request.goal_configs(world, req, world.free, 0) == \
            [[0.1, 0.2, 0.3]]
        with pytest.raises(request.InvalidRequest, match="goal has 2 joints"):
            request.goal_configs(world, _request([0.1, 0.2]), world.free, 0)
    finally:
        world.close()


def test_parameters_are_numbers_within_their_bounds():
    req = _request([0, 0, 0], [("range", "0.25"), ("bad", "x"),
                               ("low", "-1")])
    assert request.param(req, "range", 0.5, 1e-6) == 0.25
    assert request.param(req, "absent", 0.5, 1e-6) == 0.5
    with pytest.raises(request.InvalidRequest, match="must be a number"):
        request.param(req, "bad", 0.5, 0)
    with pytest.raises(request.InvalidRequest, match=">= 0"):
        request.param(req, "low", 0.5, 0)


def test_a_stage_holds_its_waypoints_row_after_row():
    st = request.stage("raw", 0.5, [[1, 2, 3], [4, 5, 6]], 3)
    assert (st.name, st.time, st.num_waypoints, st.num_joints) == \
        ("raw", 0.5, 2, 3)
    assert st.waypoints == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    assert st.num_values == 6


# A ball of radius 1 cm on prismatic joints x, y, z; one 1 cm octree cell
# whose centre is at (0.005, 0.005, 0.005): the binary stream of a root
# with child 7 (the positive octant) down to a leaf, in base64.
BALL_URDF = (
    "<robot name='ball'><link name='base'/><link name='lx'/><link name='ly'/>"
    "<link name='ball'><collision><geometry><sphere radius='0.01'/></geometry>"
    "</collision></link>" + "".join(
        f"<joint name='{j}' type='prismatic'><parent link='{p}'/><child link='{c}'/>"
        f"<axis xyz='{a}'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
        for j, p, c, a in (("x", "base", "lx", "1 0 0"), ("y", "lx", "ly", "0 1 0"),
                           ("z", "ly", "ball", "0 0 1"))) + "</robot>")


def _one_cell_stream():
    import base64
    data = bytes([0x00, 0xC0])                 # root: child 7 an inner node
    data += bytes([0x03, 0x00]) * 14           # child 0 inner, 14 levels
    data += bytes([0x02, 0x00])                # child 0 an occupied leaf
    return base64.b64encode(data).decode(), len(data)


def test_the_kit_world_checks_an_octree_of_the_scene():
    b64, n = _one_cell_stream()
    scene = f"cell\n.\noctree c binary 0.01 {n} 0 0 0 0 0 0 1\n{b64}\n"
    w = World("urdf", BALL_URDF, "moveit-scene", scene, ["x", "y", "z"])
    try:
        assert not w.free([0.005, 0.005, 0.005])    # in the cell
        assert not w.free([0.005, 0.005, 0.019])    # 9 mm above it: touching
        assert w.free([0.005, 0.005, 0.025])        # 1.5 cm above: clear
        assert w.free([-0.02, 0.005, 0.005])
    finally:
        w.close()


def test_a_peer_takes_an_octree():
    # The object's shapes as before, the octree's cell beside them
    # (tests/python/test_peer_clouds.py has the rest).
    import sys
    sys.path.insert(0, os.path.join(SOURCE, "planners", "peers"))
    from mpbpeers import peer
    b64, n = _one_cell_stream()
    box = "s\n* b\n0 0 0\n0 0 0 1\n1\nbox\n1 1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n"
    assert len(peer.parse_scene(box)) == 1
    text = box + f"octree c binary 0.01 {n} 0 0 0 0 0 0 1\n{b64}\n"
    assert len(peer.parse_scene(text)) == 1
    found, shapes = peer.read_clouds(text)
    assert [(c.id, c.count_points()) for c in found] == [("c", 1)]
    assert [(s.kind, s.cloud) for s in shapes] == [("box", "c")]


def test_limits_moved_keep_the_stop_and_move_the_deadline():
    stop = {"now": False}
    now = time.monotonic()
    limits = Limits(now - 10.0, 5.0, lambda: stop["now"])  # ended 5 s ago
    assert limits.should_stop()
    later = limits.moved(60.0)
    assert later.deadline == limits.deadline + 60.0
    assert later.start == limits.start
    assert not later.should_stop()
    stop["now"] = True          # the node's stop reaches the copy
    assert later.should_stop()
    stop["now"] = False
    assert limits.moved(-1.0).should_stop()


def test_limits_tell_setting_up_then_planning_once_each_copy_too():
    told = []
    limits = Limits(time.monotonic(), 1.0, tell=told.append)
    moved = limits.moved(2.0)
    limits.setting_up()
    moved.setting_up()          # a copy shares what was told
    limits.setting_up()
    moved.planning()
    limits.planning()
    assert told == ["setting_up", "planning"]


def test_the_peers_worker_is_given_the_limits_it_tells_through():
    # Worker.solve(req, limits=None): the node must pass the limits, or
    # the worker's SETTING_UP and PLANNING never reach the daemon.
    import sys
    from mpbplanner.limits import takes_limits
    sys.path.insert(0, os.path.join(SOURCE, "planners", "peers"))
    from mpbpeers import peer
    assert takes_limits(peer.Worker.solve.__get__(object()))
    assert not takes_limits(lambda req, cache=None: None)
    assert takes_limits(lambda req, limits: None)


def test_a_world_cache_tells_a_build_and_not_a_reuse():
    from mpbplanner.request import WorldCache
    told = []
    req = _request([0.3, -0.2, 0.1])
    with open(os.path.join(SOURCE, "scenes", "planar", "arm3.robot")) as f:
        req.robot = f.read()
    with open(os.path.join(SOURCE, "scenes", "planar", "pillars.scene")) as f:
        req.scene = f.read()
    req.robot_format = req.scene_format = "planar"
    req.robot_hash, req.scene_hash = "r", "s"
    req.joint_names = ["shoulder", "elbow", "wrist"]
    req.held_names, req.held_values = [], []
    cache = WorldCache()
    cache.get(req, Limits(time.monotonic(), 1.0, tell=told.append))
    assert told == ["setting_up", "planning"]
    assert cache.setup_time is not None
    told.clear()
    cache.get(req, Limits(time.monotonic(), 1.0, tell=told.append))
    assert told == [] and cache.setup_time is None


def test_the_kit_speaks_libmpbench_list_of_messages():
    """Every message of mpbench/messages.h, in libmpbench's order: the kit
    has its generated type and sends and listens on the same channel."""
    import ctypes

    import mpb
    from mpbplanner import node
    from mpbplanner.libmpbench import Functions

    lib = Functions(mpb_wire_type_name=(ctypes.c_char_p, ctypes.c_int),
                    mpb_wire_channel=(ctypes.c_char_p, ctypes.c_int))
    kit = {"planner_announce_t": node.ANNOUNCE,
           "plan_request_t": node.REQUEST_PREFIX,
           "plan_result_t": node.RESULT, "run_ack_t": node.ACK,
           "daemon_status_t": node.STATUS}
    listed = {}
    t = 0
    while lib.mpb_wire_channel(t) is not None:
        listed[lib.mpb_wire_type_name(t).decode()] = \
            lib.mpb_wire_channel(t).decode()
        t += 1
    assert listed == kit
    for name in listed:
        assert hasattr(mpb, name), name
