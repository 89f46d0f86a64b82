-- glint's area-light scene: soft shadows. A sphere, a box and a column on a pale floor,
-- lit by a large warm area light overhead (penumbrae that widen with the distance from
-- the occluder to the floor) and a small cool one at the side, whose shadows stay
-- sharper; a mirror sphere shows the lights' soft highlights.
-- Render it with:  glint render scenes/soft-shadows.lua
-- (--shadow-samples 8 for smoother penumbrae.)

gr.transform_order('pre')

floor_mat = gr.material({0.8, 0.8, 0.78}, {0.1, 0.1, 0.1}, 10)
wall_mat  = gr.material({0.55, 0.6, 0.7}, {0.0, 0.0, 0.0}, 1)
red    = gr.material({0.8, 0.15, 0.1}, {0.5, 0.5, 0.5}, 50)
blue   = gr.material({0.15, 0.3, 0.8}, {0.4, 0.4, 0.4}, 30)
green  = gr.material({0.2, 0.65, 0.3}, {0.4, 0.4, 0.4}, 30)
mirror = gr.material('mirror')
mirror:set_diffuse(0.05, 0.05, 0.05)
mirror:set_specular(0.7, 0.7, 0.7)
mirror:set_shininess(300)
mirror:set_reflection(0.75, 0.75, 0.8)

root = gr.node('root')

-- The floor (top at y = 0) and a back wall.
floor = gr.cube('floor')
floor:set_material(floor_mat)
floor:scale(16, 0.2, 20)
floor:translate(-8, -0.2, -8)
root:add_child(floor)

wall = gr.cube('wall')
wall:set_material(wall_mat)
wall:scale(16, 8, 0.2)
wall:translate(-8, 0, -6)
root:add_child(wall)

-- A red sphere resting on the floor.
ball = gr.sphere('ball')
ball:set_material(red)
ball:translate(-2.2, 1, -1.5)
root:add_child(ball)

-- A blue box, turned.
box = gr.cube('box')
box:set_material(blue)
box:translate(-0.5, 0, -0.5)
box:scale(1.4, 1.4, 1.4)
box:rotate('y', 30)
box:translate(0.6, 0, -2.5)
root:add_child(box)

-- A tall green column.
column = gr.cylinder('column')
column:set_material(green)
column:scale(0.4, 0.4, 3)
column:rotate('x', -90)
column:translate(2.8, 0, -3)
root:add_child(column)

-- A mirror sphere held above the floor (its shadow is the softest).
m = gr.sphere('mirror-ball')
m:set_material(mirror)
m:scale(0.6, 0.6, 0.6)
m:translate(1.6, 1.3, 0.4)
root:add_child(m)

lights = {
  -- 3×2 warm panel overhead, 6×6 shadow samples (the default is 4×4).
  gr.area_light({-0.5, 6, -0.5}, {3, 0, 0}, {0, 0, 2}, {0.85, 0.78, 0.65}, {1, 0, 0}, 6),
  -- A small cool panel at the right, tilted towards the scene, 3×3 samples.
  gr.area_light({7, 3.5, 3}, {0, 0.6, 0.0}, {-0.4, 0, 0.6}, {0.3, 0.35, 0.5}, {1, 0, 0}, 3),
}

gr.render(root, 'soft-shadows.png', 320, 200,
          {0, 3, 8}, {0, -0.3, -1}, {0, 1, 0}, 45,
          {0.2, 0.2, 0.22}, lights)
