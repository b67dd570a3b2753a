# A planar arm of three revolute joints, 1.2 m long when straight.
# Format "planar" (docs/planar-format.md).
base 0 0
link_radius 0.03
joint shoulder -3.14159 3.14159 0.5
joint elbow    -2.8 2.8 0.4
joint wrist    -2.8 2.8 0.3
