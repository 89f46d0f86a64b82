-- A scene in the lights dialect (../lights.lua), rendered three times:
--   glint render scenes/dialects/examples/lights.lua --prelude scenes/dialects/lights.lua
-- A ball over a floor, lit from above and to the side by a gr.arealight panel, then by a gr.disc_light,
-- then by a gr.sphericallight: each casts a soft shadow.

floor_m = gr.material({0.8, 0.8, 0.8}, {0, 0, 0}, 1)
ball_m = gr.material({0.8, 0.3, 0.2}, {0, 0, 0}, 1)

root = gr.node('root')
floor = gr.cube('floor')
floor:scale(20, 1, 20)
floor:translate(-10, -1, -10)
floor:set_material(floor_m)
root:add_child(floor)
ball = gr.nh_sphere('ball', {0, 1, 0}, 1)
ball:set_material(ball_m)
root:add_child(ball)

lights = {
  {'dialect-lights-arealight.png', gr.arealight({4, 4, 0}, {1, 1, 1}, {1, 0, 0}, 2, 2)},
  {'dialect-lights-disc.png', gr.disc_light({4, 4, 0}, {1, 1, 1}, {1, 0, 0}, {0, -1, 0}, 1)},
  {'dialect-lights-sphere.png', gr.sphericallight({4, 4, 0}, {1, 1, 1}, {1, 0, 0}, 1)},
}
for _, l in ipairs(lights) do
  gr.render(root, l[1], 240, 240, {0, 9, 0.001}, {0, -1, 0}, {0, 0, -1}, 50,
    {0.1, 0.1, 0.1}, {l[2]})
end
