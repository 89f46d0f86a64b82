-- A cow in a stadium: a 5 804-triangle cow (scale 0.3, about 3 units long) on a
-- 4000 × 4000 floor with 440 spheres spread over it, the camera a few units from the cow.
-- A uniform grid sized for the whole field puts the cow into one or two cells: the
-- "teapot in a stadium" case of acceleration structures. Its POV-Ray twin is
-- tools/benches/povray/stadium.pov (same camera, geometry, lights and random draws). It is a
-- benchmark scene, not in scenes/: every scene there is rendered by the golden-image
-- tests, and this one takes minutes with the uniform grid.

-- Park–Miller minimal standard generator (exact in Lua integers and in POV-Ray's doubles).
local seed = 20261129
local function rand()
  seed = (seed * 16807) % 2147483647
  return seed / 2147483647
end

local root = gr.node('root')

local ground = gr.material({0.45, 0.55, 0.35}, {0.0, 0.0, 0.0}, 1)
local hide = gr.material({0.84, 0.6, 0.53}, {0.3, 0.3, 0.3}, 20)
local paints = {
  gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 25),
  gr.material({0.2, 0.3, 0.8}, {0.5, 0.5, 0.5}, 25),
  gr.material({0.9, 0.8, 0.2}, {0.5, 0.5, 0.5}, 25),
  gr.material({0.7, 0.7, 0.7}, {0.5, 0.5, 0.5}, 25),
}

-- The field: a slab 4000 wide and deep, its top at y = 0.
local floor = gr.cube('floor')
floor:scale(4000, 1, 4000)
floor:translate(-2000, -1, -2000)
floor:set_material(ground)
root:add_child(floor)

-- 440 spheres, one per cell of a 22 × 20 lattice over the field, jittered; any that
-- would land within 60 units of the cow moves 120 units along x.
local columns, rows = 22, 20
for j = 0, rows - 1 do
  for i = 0, columns - 1 do
    local x = -2000 + (i + rand()) * 4000 / columns
    local z = -2000 + (j + rand()) * 4000 / rows
    local r = 10 + 30 * rand()
    if x * x + z * z < 60 * 60 then
      x = x + 120
    end
    local ball = gr.nh_sphere('ball' .. i .. '_' .. j, {x, r, z}, r)
    ball:set_material(paints[(i + j) % #paints + 1])
    root:add_child(ball)
  end
end

-- The cow, standing on the floor at the origin.
local cow = gr.mesh('cow', '../../scenes/cs488/a4-2021plus/cow.obj')
cow:set_material(hide)
cow:translate(0.0, 3.637, 0.0)
cow:scale(0.3, 0.3, 0.3)
root:add_child(cow)

local sun = gr.light({300, 800, 600}, {0.9, 0.9, 0.9}, {1, 0, 0})
local fill = gr.light({-400, 200, 300}, {0.3, 0.3, 0.35}, {1, 0, 0})

gr.render(root, 'stadium.png', 1024, 768,
  {0, 2, 7}, {0, -0.15, -1}, {0, 1, 0}, 40,
  {0.3, 0.3, 0.3}, {sun, fill},
  {aa = 'none', background = {0.55, 0.7, 0.9}})
