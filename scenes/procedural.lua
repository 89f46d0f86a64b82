-- glint's procedural-texture scene: no image at all. A checker floor to the horizon
-- (gr.checker, box-filtered by each pixel's footprint so it does not shimmer), and, left
-- to right, a noise sphere (gr.noise, 4 octaves), a marble box (gr.marble), a wood
-- plank (gr.wood, rings around its length) and a sphere bumped by noise alone
-- (m:set_bump(gr.noise(...))). Each pattern lives in its primitive's own space: it
-- moves, turns and scales with the object. Render it with:
--   glint render scenes/procedural.lua

gr.transform_order('pre')

floor_material = gr.material('checker-floor')
-- The floor is the unit cube scaled by 400: cells of 1/400 of it are 1 unit wide.
floor_material:set_diffuse(gr.checker({0.85, 0.85, 0.8}, {0.15, 0.2, 0.3}, 1 / 400))
floor_material:set_specular(0.1, 0.1, 0.1)
floor_material:set_shininess(10)

clouds = gr.material('noise')
clouds:set_diffuse(gr.noise({0.95, 0.9, 0.8}, {0.2, 0.35, 0.7}, 2.5, 4))
clouds:set_specular(0.3, 0.3, 0.3)
clouds:set_shininess(40)

stone = gr.material('marble')
stone:set_diffuse(gr.marble({0.92, 0.9, 0.86}, {0.3, 0.28, 0.32}, 3, 1.5, 5))
stone:set_specular(0.5, 0.5, 0.5)
stone:set_shininess(80)

oak = gr.material('wood')
oak:set_diffuse(gr.wood({0.8, 0.55, 0.3}, {0.5, 0.28, 0.12}, 8, 0.15, 3))
oak:set_specular(0.2, 0.2, 0.2)
oak:set_shininess(20)

hammered = gr.material('bumped')
hammered:set_diffuse(0.7, 0.72, 0.75)
hammered:set_specular(0.6, 0.6, 0.6)
hammered:set_shininess(60)
hammered:set_bump(gr.noise({0, 0, 0}, {1, 1, 1}, 4, 3), 0.08)

root = gr.node('root')

floor = gr.cube('floor')
floor:set_material(floor_material)
floor:translate(-0.5, -1, -0.5)
floor:scale(400, 1, 400)
root:add_child(floor)

ball = gr.sphere('noise-sphere')
ball:set_material(clouds)
ball:translate(-3.6, 1, 0)
root:add_child(ball)

block = gr.cube('marble-box')
block:set_material(stone)
block:translate(-0.5, 0, -0.5)
block:scale(1.6, 1.6, 1.6)
block:rotate('y', 25)
block:translate(-1.1, 0, 0)
root:add_child(block)

plank = gr.cube('wood-plank')
plank:set_material(oak)
plank:translate(-0.5, -0.5, -0.5)
plank:scale(1.2, 0.9, 1.8)
plank:rotate('y', -20)
plank:translate(1.3, 0.45, 0.2)
root:add_child(plank)

bumped = gr.sphere('bumped-sphere')
bumped:set_material(hammered)
bumped:translate(3.7, 1, 0)
root:add_child(bumped)

light = gr.light({-5, 9, 8}, {0.85, 0.85, 0.85}, {1, 0, 0})
fill = gr.light({6, 5, 4}, {0.3, 0.3, 0.35}, {1, 0, 0})

gr.render(root, 'procedural.png', 480, 270, {0, 3, 10}, {0, -0.25, -1}, {0, 1, 0}, 40,
          {0.35, 0.35, 0.35}, {light, fill})
