"""rrt_connect.py - bidirectional RRT (Kuffner and LaValle's RRT-Connect) in
joint space, and a shortcut pass over its path.

Two trees grow towards random samples and then greedily towards each
other; the goal tree may have several roots (configurations sampled inside
a goal region). Motions are checked every `resolution` rad in joint space,
continuous joints the short way round, as the daemon's verifier does.
"""
import math

TRAPPED, ADVANCED, REACHED = 0, 1, 2


class Space:
    """Joint-space geometry: distances, interpolation, sampling, motion
    checks, all through one World."""

    def __init__(self, world, resolution, rng):
        self.world = world
        self.resolution = resolution
        self.rng = rng
        self.checks = 0

    def delta(self, a, b):
        """b - a per joint, the short way round for continuous joints."""
        d = [y - x for x, y in zip(a, b)]
        for j, wraps in enumerate(self.world.wraps):
            if wraps:
                d[j] = math.remainder(d[j], 2.0 * math.pi)
        return d

    def distance(self, a, b):
        return math.sqrt(sum(x * x for x in self.delta(a, b)))

    def toward(self, a, b, step):
        """From a toward b, at most `step` away."""
        d = self.delta(a, b)
        n = math.sqrt(sum(x * x for x in d))
        if n <= step:
            return [x + y for x, y in zip(a, d)], True
        s = step / n
        return [x + s * y for x, y in zip(a, d)], False

    def sample(self):
        w = self.world
        return [self.rng.uniform(-math.pi, math.pi) if w.wraps[j]
                else self.rng.uniform(w.lower[j], w.upper[j])
                for j in range(w.num_joints)]

    def free(self, q):
        self.checks += 1
        return self.world.free(q)

    def motion_free(self, a, b):
        """a and b assumed free; every point between them checked."""
        d = self.delta(a, b)
        n = max(1, math.ceil(math.sqrt(sum(x * x for x in d)) / self.resolution))
        for i in range(1, n):
            s = i / n
            if not self.free([x + s * y for x, y in zip(a, d)]):
                return False
        return True


class Tree:
    """Vertices and their parents; nearest neighbour by linear scan, which
    is fast enough for the trees a first solution needs."""

    def __init__(self, space, roots):
        self.space = space
        self.nodes = list(roots)
        self.parent = [-1] * len(self.nodes)

    def nearest(self, q):
        dist = self.space.distance
        return min(range(len(self.nodes)), key=lambda i: dist(self.nodes[i], q))

    def add(self, q, parent):
        self.nodes.append(q)
        self.parent.append(parent)
        return len(self.nodes) - 1

    def path_to_root(self, i):
        out = []
        while i >= 0:
            out.append(self.nodes[i])
            i = self.parent[i]
        return out


def _extend(tree, q, step):
    space = tree.space
    near = tree.nearest(q)
    new, reached = space.toward(tree.nodes[near], q, step)
    if not space.free(new) or not space.motion_free(tree.nodes[near], new):
        return TRAPPED, -1
    return (REACHED if reached else ADVANCED), tree.add(new, near)


def _connect(tree, q, step):
    while True:
        state, i = _extend(tree, q, step)
        if state != ADVANCED:
            return state, i


def plan(space, start, goals, step, should_stop):
    """A path (list of configurations) from start to one of goals, or None
    when should_stop() (the kit's Limits.should_stop) says so first."""
    a, b = Tree(space, [start]), Tree(space, goals)
    while not should_stop():
        state, i = _extend(a, space.sample(), step)
        if state != TRAPPED:
            state, j = _connect(b, a.nodes[i], step)
            if state == REACHED:
                half_a, half_b = a.path_to_root(i), b.path_to_root(j)
                if a.nodes[0] is not start:       # trees were swapped
                    half_a, half_b = half_b, half_a
                return half_a[::-1] + half_b[1:]
        a, b = b, a
    return None


def shortcut(space, path, attempts, should_stop):
    """Replace stretches of the path by straight motions where they are
    free: pick two waypoints at random, join them if nothing is between."""
    path = list(path)
    for _ in range(attempts):
        if len(path) < 3 or should_stop():
            break
        i = space.rng.randrange(len(path) - 2)
        j = space.rng.randrange(i + 2, len(path))
        if space.motion_free(path[i], path[j]):
            del path[i + 1:j]
    return path
