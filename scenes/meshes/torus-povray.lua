-- glint's twin of tools/benches/povray/torus.pov: the smooth torus of make_torus.py (OBJ
-- vertex normals), two point lights, A4 Phong, no anti-aliasing. POV-Ray renders the same
-- mesh as smooth triangles (mesh2 with normal_vectors); tests/shading.rs compares the two
-- images (tests/golden/povray-torus.png, made by tools/benches/povray/torus-reference.sh).

gr.transform_order('pre')

copper = gr.material({0.8, 0.45, 0.25}, {0.6, 0.6, 0.6}, 30)

root = gr.node('root')
torus = gr.mesh('torus', 'torus.obj')
torus:set_material(copper)
torus:rotate('x', -20)
root:add_child(torus)

light = gr.light({-3, -4, 5}, {0.9, 0.9, 0.9}, {1, 0, 0})
rim = gr.light({4, 1, 1}, {0.3, 0.4, 0.6}, {1, 0, 0})

gr.render(root, 'torus-povray.png', 200, 150,
  {0, -3.4, 2.4}, {0, 3.4, -2.4}, {0, 0, 1}, 30,
  {0.15, 0.15, 0.15}, {light, rim},
  {aa = 'none', background = {0.1, 0.1, 0.15}})
