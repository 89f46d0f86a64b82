-- Random triangles (tools/benches/random_triangles.py) read from mesh.obj beside this file
-- (tools/benches/meshload.sh writes it there), seen from +z as random-triangles.lua sees
-- them, at 640×480: the second row of the mesh-loading bench.
local soup = gr.mesh('soup', 'mesh.obj')
soup:set_material(gr.material({0.7, 0.7, 0.7}, {0.0, 0.0, 0.0}, 1))
local root = gr.node('root')
root:add_child(soup)
gr.render(root, 'image.png', 640, 480,
  {0.5, 0.5, 3}, {0, 0, -1}, {0, 1, 0}, 40,
  {0.1, 0.1, 0.1}, {gr.light({0.5, 3, 3}, {0.9, 0.9, 0.9}, {1, 0, 0})},
  {aa = 'none'})
