-- glint's texture scene: every primitive wearing the UV-grid texture (red rises with u,
-- green with v, dark lines on each cell's low-u and low-v edges, a white dot in the
-- u = v = 0 cell), a bump-mapped sphere, and a floor whose shine comes from a specular
-- map. Back row, left to right: sphere (pole up), box, cylinder, cone (tip up), torus
-- (facing the camera). Front: an inline quad with its own UVs (repeating twice), a
-- pyramid without UVs (planar projection), the bump-mapped sphere.
-- The textures (in ../textures/) are made by tools/examples/make_textures.rs
-- (cargo run --example make_textures). Render it with:  glint render scenes/textures.lua
-- UV view:  glint render scenes/textures.lua --debug uv

gr.transform_order('pre')

grid = gr.material('uv-grid')
grid:set_diffuse('../textures/uv-grid.png')
grid:set_specular(0.15, 0.15, 0.15)
grid:set_shininess(20)

bumpy = gr.material('bumpy')
bumpy:set_diffuse(0.75, 0.3, 0.15)
bumpy:set_specular(0.5, 0.5, 0.5)
bumpy:set_shininess(50)
bumpy:set_bump('../textures/bumps.png', 0.015)

floor_material = gr.material('floor')
floor_material:set_diffuse(0.45, 0.47, 0.5)
floor_material:set_specular('../textures/bumps.png')
floor_material:set_shininess(10)

root = gr.node('root')

floor = gr.mesh('floor', {{-8, 0, -6}, {8, 0, -6}, {8, 0, 6}, {-8, 0, 6}}, {{0, 3, 2, 1}},
                {{0, 0}, {4, 0}, {4, 3}, {0, 3}})
floor:set_material(floor_material)
root:add_child(floor)

sphere = gr.sphere('sphere')
sphere:set_material(grid)
sphere:scale(0.9, 0.9, 0.9)
sphere:rotate('x', -90)
sphere:translate(-4.6, 0.9, -2)
root:add_child(sphere)

box = gr.cube('box')
box:set_material(grid)
box:translate(-0.5, 0, -0.5)
box:scale(1.5, 1.5, 1.5)
box:rotate('y', 30)
box:translate(-2.3, 0, -2)
root:add_child(box)

cylinder = gr.cylinder('cylinder')
cylinder:set_material(grid)
cylinder:scale(0.7, 0.7, 1.6)
cylinder:rotate('x', -90)
cylinder:translate(0, 0, -2)
root:add_child(cylinder)

cone = gr.cone('cone', 0, 1)
cone:set_material(grid)
cone:scale(0.8, 0.8, 1.7)
cone:rotate('x', 90)
cone:translate(2.3, 1.7, -2)
root:add_child(cone)

torus = gr.torus('torus', 0.75, 0.35)
torus:set_material(grid)
torus:translate(4.6, 1.1, -2)
root:add_child(torus)

quad = gr.mesh('quad', {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}},
               {{0, 0}, {2, 0}, {2, 2}, {0, 2}})
quad:set_material(grid)
quad:scale(1.6, 1.6, 1)
quad:rotate('y', 20)
quad:translate(-4.6, 0.05, 2.5)
root:add_child(quad)

pyramid = gr.mesh('pyramid',
                  {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 1.5, 0}},
                  {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}})
pyramid:set_material(grid)
pyramid:rotate('y', 20)
pyramid:translate(-1.0, 0, 3.0)
root:add_child(pyramid)

ball = gr.sphere('bump-sphere')
ball:set_material(bumpy)
ball:scale(0.9, 0.9, 0.9)
ball:rotate('x', -90)
ball:translate(2.4, 0.9, 3.5)
root:add_child(ball)

light = gr.light({-4, 9, 9}, {0.85, 0.85, 0.85}, {1, 0, 0})
-- Behind the objects, so the floor's specular map shines towards the camera in front.
fill = gr.light({0, 6, -6}, {0.35, 0.35, 0.4}, {1, 0, 0})

gr.render(root, 'textures.png', 480, 270, {0, 4.2, 11.5}, {0, -0.3, -1}, {0, 1, 0}, 40,
          {0.35, 0.35, 0.35}, {light, fill})
