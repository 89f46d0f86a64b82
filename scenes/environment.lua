-- glint's environment scene: an HDR sky (render option `environment`) seen by the camera
-- and in a mirror ball and a glass ball; a matte ball beside them shows that the map lights
-- nothing (Whitted: only its point light and the ambient term do). The sky
-- (../textures/sky.hdr, Radiance RGBE: a blue dome, coloured bands round the horizon, a
-- brown ground and a sun of radiance up to 9) is made by tools/oracle/environment.py.
-- Render it with:  glint render scenes/environment.lua   (--output x.exr keeps the HDR)

gr.transform_order('pre')

mirror = gr.material({0, 0, 0}, {0, 0, 0}, 1)
mirror:set_reflection(0.95)

glass = gr.material({0, 0, 0}, {0.6, 0.6, 0.6}, 300)
glass:set_refraction(1.5)

matte = gr.material({0.7, 0.55, 0.35}, {0.3, 0.3, 0.3}, 25)

root = gr.node('root')
local function ball(name, m, x, r)
    local b = gr.nh_sphere(name, {x, r - 1, 0}, r)
    b:set_material(m)
    root:add_child(b)
end
ball('mirror', mirror, -2.3, 1)
ball('glass', glass, 0, 1)
ball('matte', matte, 2.1, 0.8)

sun = gr.light({-6, 8, 10}, {0.9, 0.9, 0.9}, {1, 0, 0})
gr.render(root, 'environment.png', 320, 180, {0, -0.2, 7.5}, {0, 0.6, -7.5}, {0, 1, 0}, 50,
          {0.15, 0.15, 0.15}, {sun},
          {environment = '../textures/sky.hdr', environment_rotation = 215})
