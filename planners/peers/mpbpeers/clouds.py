"""clouds.py - a scene's octrees and point clouds (its `octree` and
`spheres` lines after the '.', docs/scenes.md) as libmpbench reads them,
through ctypes: mpb_scene_open_text() and mpb_scene_object_at() (scene.h),
so that the base64, OctoMap's stream and the merging of cells into
boxes are libmpbench's, the code the daemon verifies with, and not a
second reading in Python.

read(text) gives one Cloud per such object: its id, its kind ("octree"
or "spheres"), its pose in the world (row-major rotation, translation)
and, in the object's frame, its boxes (an octree's occupied cells,
merged as libmpbench merges them: each a centre and side lengths) or
its sphere centres with their radius. Cloud.points() gives what a
library's point cloud API takes: an octree's leaf cells' centres
(every merged box cut back into cells of the resolution, each centre
exactly OctoMap's for its key) or the spheres' centres, with the side
of the cell each stands for (Cloud.cell: the octree's resolution; for
spheres their diameter, as MPLib's OcTree documents its resolution:
"the diameter of a point"). Cloud.octomap_bt() gives an octree's cells
as an OctoMap .bt file, written by libmpbench (mpb_octree_write()), for
a library that reads OctoMap's files.
"""
import ctypes
from ctypes import (POINTER, Structure, byref, c_char_p, c_double, c_float,
                    c_int, c_size_t, c_void_p, create_string_buffer)

from mpbplanner.libmpbench import declare

SHAPES, OCTREE, SPHERES = 0, 1, 2      # mpb_scene_kind
SHAPE_BOX, SHAPE_SPHERE = 0, 1         # mpb_shape_type
# At most this many points from one cloud (leaf cells of an octree whose
# merged boxes fill volumes, or spheres): 4 x MPB_OCTREE_MAX_CELLS.
MAX_POINTS = 2000000


class _Pose(Structure):            # pose.h: mpb_pose
    _fields_ = [("R", c_double * 9), ("t", c_double * 3)]


class _Geometry(Structure):        # collision.h: mpb_geometry
    _fields_ = [("type", c_int), ("dims", c_double * 4), ("mesh", c_void_p)]


class _Shape(Structure):           # scene.h: mpb_scene_shape
    _fields_ = [("geometry", _Geometry), ("pose", _Pose),
                ("color", c_float * 4), ("line", c_int)]


class _Object(Structure):          # scene.h: mpb_scene_object
    _fields_ = [("id", c_char_p), ("pose", _Pose), ("num_shapes", c_int),
                ("shapes", POINTER(_Shape)), ("num_subframes", c_int),
                ("subframes", c_void_p), ("attached_link", c_char_p),
                ("num_touch_links", c_int), ("touch_links", POINTER(c_char_p)),
                ("line", c_int), ("attach_line", c_int), ("kind", c_int),
                ("resolution", c_double)]


_parse = declare("mpb_scene_open_text", c_int, c_char_p, POINTER(c_void_p),
                 c_char_p, c_size_t)
_free = declare("mpb_scene_close", None, c_void_p)
_num_objects = declare("mpb_scene_num_objects", c_int, c_void_p)
_object_at = declare("mpb_scene_object_at", POINTER(_Object), c_void_p, c_int)
_tree_create = declare("mpb_octree_create", c_int, c_double, POINTER(c_void_p))
_tree_add = declare("mpb_octree_add_point", c_int, c_void_p, POINTER(c_double))
_tree_write = declare("mpb_octree_write", c_int, c_void_p, c_int,
                      POINTER(c_void_p), POINTER(c_size_t))
_tree_destroy = declare("mpb_octree_destroy", None, c_void_p)
_libc_free = ctypes.CDLL(None).free
_libc_free.argtypes = [c_void_p]
_libc_free.restype = None


class CloudError(Exception):
    """A scene libmpbench refuses, or a cloud too large for points()."""


class Cloud:
    """An octree or spheres object: id, kind ("octree", "spheres"),
    resolution (an octree's finest cell; the spheres' radius), rotation
    (3x3, rows) and translation of its pose in the world, and in its
    frame boxes [(centre, sides)] (an octree) or centres (spheres)."""

    def __init__(self, oid, kind, resolution, rotation, translation,
                 boxes=None, centres=None):
        self.id, self.kind, self.resolution = oid, kind, resolution
        self.rotation, self.translation = rotation, translation
        self.boxes = boxes or []
        self.centres = centres or []

    @property
    def cell(self):
        """The side of the cell one of points() stands for (m)."""
        return self.resolution if self.kind == "octree" else \
            2.0 * self.resolution

    def matrix(self):
        """The pose as a 4x4 homogeneous matrix, nested lists."""
        r, t = self.rotation, self.translation
        return [r[0] + [t[0]], r[1] + [t[1]], r[2] + [t[2]],
                [0.0, 0.0, 0.0, 1.0]]

    def is_identity(self):
        """True when the pose is the identity: object frame = world."""
        r, t = self.rotation, self.translation
        return all(r[i][j] == (1.0 if i == j else 0.0)
                   for i in range(3) for j in range(3)) and \
            all(v == 0.0 for v in t)

    def count_points(self):
        """How many points points() gives."""
        if self.kind == "spheres":
            return len(self.centres)
        res = self.resolution
        return sum(max(int(round(d[0] / res)), 1) *
                   max(int(round(d[1] / res)), 1) *
                   max(int(round(d[2] / res)), 1) for _, d in self.boxes)

    def points(self, world=False):
        """The leaf cells' centres (an octree) or the spheres' centres, in
        the object's frame (world: in the world's). CloudError beyond
        MAX_POINTS."""
        n = self.count_points()
        if n > MAX_POINTS:
            raise CloudError(f"{self.kind} '{self.id}': {n} points, more than "
                             f"{MAX_POINTS} a point cloud is given")
        if self.kind == "spheres":
            out = [list(c) for c in self.centres]
        else:
            res = self.resolution
            out = []
            for c, d in self.boxes:
                # The box's lower corner is a multiple of the resolution
                # (its cells' keys): each centre is (key + 0.5) x res.
                lo = [int(round((c[k] - d[k] / 2) / res)) for k in range(3)]
                cnt = [max(int(round(d[k] / res)), 1) for k in range(3)]
                for i in range(cnt[0]):
                    x = (lo[0] + i + 0.5) * res
                    for j in range(cnt[1]):
                        y = (lo[1] + j + 0.5) * res
                        for k in range(cnt[2]):
                            out.append([x, y, (lo[2] + k + 0.5) * res])
        if world:
            r, t = self.rotation, self.translation
            out = [[r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i]
                    for i in range(3)] for p in out]
        return out

    def octomap_bt(self):
        """An octree's cells, in its own frame, as the bytes of an OctoMap
        .bt file at its resolution (header and OcTree::writeBinaryData()'s
        stream), libmpbench's tree of points()' cells written by
        mpb_octree_write(). CloudError for spheres, or a tree libmpbench
        refuses."""
        if self.kind != "octree":
            raise CloudError(f"{self.kind} '{self.id}': not an octree")
        tree = c_void_p()
        if _tree_create(self.resolution, byref(tree)) != 0:
            raise CloudError(f"octree '{self.id}': resolution "
                             f"{self.resolution} refused")
        try:
            p = (c_double * 3)()
            for q in self.points():
                p[0], p[1], p[2] = q
                if _tree_add(tree, p) != 0:
                    raise CloudError(f"octree '{self.id}': a cell refused")
            data, size = c_void_p(), c_size_t()
            if _tree_write(tree, 1, byref(data), byref(size)) != 0:
                raise CloudError(f"octree '{self.id}': not written")
            try:
                return ctypes.string_at(data, size.value)
            finally:
                _libc_free(data)
        finally:
            _tree_destroy(tree)


def read(text):
    """The octree and spheres objects of a scene text, in file order."""
    handle = c_void_p()
    err = create_string_buffer(512)
    if _parse(text.encode(), byref(handle), err, len(err)) != 0:
        raise CloudError(err.value.decode(errors="replace"))
    try:
        out = []
        for i in range(_num_objects(handle)):
            o = _object_at(handle, i).contents
            if o.kind not in (OCTREE, SPHERES):
                continue
            rot = [list(o.pose.R[3 * r:3 * r + 3]) for r in range(3)]
            trans = list(o.pose.t)
            boxes, centres = [], []
            for k in range(o.num_shapes):
                s = o.shapes[k]
                centre = list(s.pose.t)
                if o.kind == OCTREE:
                    if s.geometry.type != SHAPE_BOX:
                        raise CloudError(f"octree '{o.id.decode()}': a shape "
                                         f"that is not a box")
                    boxes.append((centre, list(s.geometry.dims[:3])))
                else:
                    centres.append(centre)
            out.append(Cloud(o.id.decode(errors="replace"),
                             "octree" if o.kind == OCTREE else "spheres",
                             o.resolution, rot, trans, boxes, centres))
        return out
    finally:
        _free(handle)
