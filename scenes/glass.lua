-- glint's glass scene: dielectrics (m:set_refraction). A glass ball with an air bubble
-- in it, an upright glass ring, and a tank of water with a glass ball sunk in it, in
-- front of coloured columns on a checkerboard floor; the floor and columns show, bent
-- and inverted, through the glass.
-- Render it with:  glint render scenes/glass.lua

gr.transform_order('pre')

white = gr.material({0.85, 0.85, 0.85}, {0.2, 0.2, 0.2}, 20)
dark  = gr.material({0.12, 0.12, 0.16}, {0.2, 0.2, 0.2}, 20)
red   = gr.material({0.8, 0.15, 0.1}, {0.5, 0.5, 0.5}, 50)
blue  = gr.material({0.15, 0.3, 0.8}, {0.5, 0.5, 0.5}, 50)
green = gr.material({0.15, 0.65, 0.25}, {0.5, 0.5, 0.5}, 50)

-- Clear dielectrics: no diffuse colour, a sharp highlight; Fresnel does the rest.
glass = gr.material('glass')
glass:set_diffuse(0, 0, 0)
glass:set_specular(0.6, 0.6, 0.6)
glass:set_shininess(300)
glass:set_refraction(1.5)

water = gr.material('water')
water:set_diffuse(0, 0, 0)
water:set_specular(0.4, 0.4, 0.4)
water:set_shininess(150)
water:set_refraction(1.33)

-- An air bubble: index 1 inside glass (leaving it pops back to the glass).
air = gr.material('air')
air:set_diffuse(0, 0, 0)
air:set_specular(0.3, 0.3, 0.3)
air:set_shininess(150)
air:set_refraction(1.0)

root = gr.node('root')

-- The floor: 12×11 tiles, top at y = 0.
for i = 0, 11 do
  for j = 0, 10 do
    local tile = gr.cube('tile' .. i .. '_' .. j)
    tile:set_material(((i + j) % 2 == 0) and white or dark)
    tile:scale(1, 0.2, 1)
    tile:translate(i - 6, -0.2, j - 6)
    root:add_child(tile)
  end
end

-- Coloured columns behind the glass.
local colours = {red, green, blue, red, green}
for k = 0, 4 do
  local column = gr.cylinder('column' .. k)
  column:set_material(colours[k + 1])
  column:scale(0.25, 0.25, 2.6)
  column:rotate('x', -90)
  column:translate(-3.2 + 1.6 * k, 0, -3.2)
  root:add_child(column)
end

-- A glass ball with an off-centre air bubble.
ball = gr.nh_sphere('ball', {-2.3, 1.0, 0.2}, 1.0)
ball:set_material(glass)
root:add_child(ball)
bubble = gr.nh_sphere('bubble', {-2.05, 1.25, 0.35}, 0.35)
bubble:set_material(air)
root:add_child(bubble)

-- An upright glass ring.
ring = gr.torus('ring', 0.75, 0.22)
ring:set_material(glass)
ring:rotate('y', 20)
ring:translate(0.1, 0.97, -0.6)
root:add_child(ring)

-- A tank of water with a glass ball sunk in it (glass in water).
tank = gr.cube('tank')
tank:set_material(water)
tank:scale(1.7, 1.5, 1.5)
tank:translate(1.35, 0.001, -0.3)
root:add_child(tank)
sunk = gr.nh_sphere('sunk', {2.2, 0.55, 0.45}, 0.5)
sunk:set_material(glass)
root:add_child(sunk)

lights = {
  gr.light({-5, 8, 7}, {0.75, 0.75, 0.7}, {1, 0, 0}),
  gr.light({6, 5, 5}, {0.35, 0.3, 0.45}, {1, 0, 0}),
}

gr.render(root, 'glass.png', 512, 320,
          {0, 2.6, 7.5}, {0, -0.3, -1}, {0, 1, 0}, 45,
          {0.25, 0.25, 0.3}, lights,
          {background = {top = {0.55, 0.7, 0.95}, bottom = {0.95, 0.85, 0.7}}})
