"""test_peer_clouds.py - a scene's octrees and point clouds as the peers
hand them to their libraries (planners/peers/mpbpeers/clouds.py and
peer.read_clouds), read by libmpbench through ctypes, tested here
without any library: the boxes are libmpbench's merged cells, the
points each leaf cell's centre (a pruned block of eight cut back into
its cells), a posed octree's points in the world where its pose puts
them, a cloud's spheres their centres with cells of their diameter,
and the objects' own shapes read as before."""
import ctypes
import os
import sys
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_void_p

SOURCE = os.environ["MPB_SOURCE"]
sys.path.insert(0, os.path.join(SOURCE, "planners", "peers"))
from mpbplanner.libmpbench import declare  # noqa: E402
from mpbpeers import clouds, peer  # noqa: E402

_create = declare("mpb_octree_create", c_int, c_double, POINTER(c_void_p))
_add = declare("mpb_octree_add_point", c_int, c_void_p, POINTER(c_double))
_free = declare("mpb_octree_destroy", None, c_void_p)
_text = declare("mpb_scene_octree_text", c_int, c_void_p, c_char_p,
                POINTER(c_double), POINTER(c_void_p))
_libc = ctypes.CDLL(None)
_libc.free.argtypes = [c_void_p]

RES = 0.02
BOX = """* table
0 0 0
0 0 0 1
1
box
0.5 0.5 0.1
1 0 0.05
0 0 0 1
0 0 0 0
0
"""


def _octree_text(cells, oid="map", pose=None):
    """The octree line (mpb_scene_octree_text) of a tree whose occupied
    leaf cells are those of the integer keys in cells."""
    tree = c_void_p()
    assert _create(RES, byref(tree)) == 0
    try:
        for i, j, k in cells:
            p = (c_double * 3)((i + 0.5) * RES, (j + 0.5) * RES, (k + 0.5) * RES)
            assert _add(tree, p) == 0
        out = c_void_p()
        arg = (c_double * 7)(*pose) if pose else None
        assert _text(tree, oid.encode(), arg, byref(out)) == 0
        text = ctypes.string_at(out).decode()
        _libc.free(out)
        return text
    finally:
        _free(tree)


# A block of 2 x 2 x 2 (OctoMap prunes it into its parent cell) at keys
# 0..1, a lone cell at (5, 0, 0) and a row of three at y = 3.
BLOCK = [(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
CELLS = BLOCK + [(5, 0, 0), (0, 3, 0), (1, 3, 0), (2, 3, 0)]


def _keys(points):
    return sorted(tuple(int(round(v / RES - 0.5)) for v in p) for p in points)


def test_octree_points_are_every_leaf_cell_centre():
    text = "scene\n" + BOX + ".\n" + _octree_text(CELLS)
    found, shapes = peer.read_clouds(text)
    assert [(c.id, c.kind, c.resolution) for c in found] == \
        [("map", "octree", RES)]
    c = found[0]
    assert c.cell == RES and c.is_identity()
    points = c.points()
    assert c.count_points() == len(points) == len(CELLS)
    assert _keys(points) == sorted(CELLS)
    for p in points:            # exactly (key + 0.5) x resolution
        assert all(abs(v / RES - round(v / RES - 0.5) - 0.5) < 1e-9 for v in p)


def test_octree_boxes_are_libmpbench_merged_cells():
    text = "scene\n" + BOX + ".\n" + _octree_text(CELLS)
    found, shapes = peer.read_clouds(text)
    boxes = [s for s in shapes if s.cloud == "map"]
    assert len(boxes) == len(shapes) == len(found[0].boxes)
    # Fewer boxes than cells, their volume the cells'.
    assert len(boxes) < len(CELLS)
    volume = sum(s.dims[0] * s.dims[1] * s.dims[2] for s in boxes)
    assert abs(volume - len(CELLS) * RES ** 3) < 1e-12
    assert all(s.kind == "box" and s.quat == [0.0, 0.0, 0.0, 1.0]
               for s in boxes)
    # The object's own shapes as parse_scene reads them, cloud None.
    own = peer.parse_scene(text)
    assert [(s.kind, s.dims, s.cloud) for s in own] == \
        [("box", [0.5, 0.5, 0.1], None)]


def test_posed_octree_points_in_the_world():
    # A quarter turn about z, then 1 m along x.
    h = 0.5 ** 0.5
    text = "scene\n.\n" + _octree_text([(5, 0, 0)], "posed",
                                       [1, 0, 0, 0, 0, h, h])
    c = peer.read_clouds(text)[0][0]
    assert not c.is_identity()
    (x, y, z), = c.points()
    assert (x, y, z) == (5.5 * RES, 0.5 * RES, 0.5 * RES)
    (wx, wy, wz), = c.points(world=True)
    assert abs(wx - (1 - 0.5 * RES)) < 1e-12
    assert abs(wy - 5.5 * RES) < 1e-12 and abs(wz - 0.5 * RES) < 1e-12
    assert all(abs(a - b) < 1e-12 for a, b in zip(c.quat, [0, 0, h, h]))
    box, = peer.read_clouds(text)[1]
    assert all(abs(a - b) < 1e-12 for a, b in zip(box.position, [wx, wy, wz]))


def test_spheres_centres_and_cells_of_their_diameter():
    text = ("scene\n.\nspheres pts 0.005 3 0 0 0.5 0 0 0 1\n"
            "0.1 0.2 0.3\n-0.1 0 0\n0 0 0.01\n")
    found, shapes = peer.read_clouds(text)
    c, = found
    assert (c.id, c.kind, c.resolution, c.cell) == ("pts", "spheres", 0.005,
                                                    0.01)
    assert c.points() == [[0.1, 0.2, 0.3], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.01]]
    assert c.points(world=True)[0] == [0.1, 0.2, 0.8]
    assert [(s.kind, s.dims, s.cloud) for s in shapes] == \
        [("sphere", [0.005], "pts")] * 3
    assert shapes[0].position == [0.1, 0.2, 0.8]


def test_no_clouds_and_bad_text():
    assert peer.read_clouds("scene\n" + BOX + ".\n") == ([], [])
    try:
        peer.read_clouds("scene\n.\nspheres pts 0.005 2 0 0 0 0 0 0 1\n1 2 3\n")
    except peer.InvalidRequest as e:
        assert "spheres" in str(e)
    else:
        raise AssertionError("a truncated spheres line was taken")


def test_points_bounded():
    c = clouds.Cloud("big", "octree", 0.01, [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
                     [0, 0, 0], boxes=[([0, 0, 0], [2.0, 2.0, 2.0])])
    assert c.count_points() == 200 ** 3
    try:
        c.points()
    except clouds.CloudError as e:
        assert "8000000 points" in str(e)
    else:
        raise AssertionError("8e6 points were given")


def test_octree_data_is_not_read_as_lines():
    # parse_scene skips an octree's base64 (which may hold any word) but
    # still refuses an attach line after it.
    tree = _octree_text(CELLS)
    assert peer.parse_scene("scene\n" + BOX + ".\n" + tree + "# end\n") != []
    try:
        peer.parse_scene("scene\n" + BOX + ".\n" + tree + "attach table l\n")
    except peer.InvalidRequest as e:
        assert "attach" in str(e)
    else:
        raise AssertionError("an attach line after an octree was taken")


_from_bytes = declare("mpb_octree_create_from_bytes", c_int, c_char_p,
                      ctypes.c_size_t, c_char_p, POINTER(c_void_p), c_char_p,
                      ctypes.c_size_t)
_num_cells = declare("mpb_octree_num_cells", c_int, c_void_p)
_cell = declare("mpb_octree_cell", c_int, c_void_p, c_int, POINTER(c_double),
                POINTER(c_double))


def test_octree_as_an_octomap_file_holds_its_cells():
    # A posed octree's .bt (for Tesseract's URDF reader): OctoMap's
    # header at its resolution, and read back by libmpbench the same
    # cells in the octree's own frame (the block of eight pruned).
    h = 0.5 ** 0.5
    text = "scene\n.\n" + _octree_text(CELLS, "posed", [1, 0, 0, 0, 0, h, h])
    c = peer.read_clouds(text)[0][0]
    data = c.octomap_bt()
    lines = data.split(b"\n")
    assert lines[0] == b"# Octomap OcTree binary file"
    assert b"id OcTree" in lines and b"res 0.02" in lines
    tree = c_void_p()
    err = ctypes.create_string_buffer(256)
    assert _from_bytes(data, len(data), b"bt", byref(tree), err,
                       len(err)) == 0, err.value
    try:
        n = _num_cells(tree)
        assert n == len(CELLS) - 7
        cells = []
        for i in range(n):
            centre, side = (c_double * 3)(), c_double()
            assert _cell(tree, i, centre, byref(side)) == 0
            cells.append((round(side.value / RES), list(centre)))
        assert sorted((s, _keys([p])[0]) for s, p in cells if s == 1) == \
            sorted((1, k) for k in CELLS if k not in BLOCK)
        assert [(s, p) for s, p in cells if s != 1] == [(2, [RES] * 3)]
    finally:
        _free(tree)


def test_spheres_are_no_octomap_file():
    c = clouds.Cloud("pts", "spheres", 0.005, [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
                     [0, 0, 0], centres=[[0, 0, 0]])
    try:
        c.octomap_bt()
    except clouds.CloudError as e:
        assert "not an octree" in str(e)
    else:
        raise AssertionError("spheres were written as an octree")
