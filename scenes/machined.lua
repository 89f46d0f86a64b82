-- glint's machined-parts scene: opaque CSG only (no glass), on a checkerboard floor.
-- A die (a cube ∩ a sphere, minus its 21 drilled pips, which keep the drill's dark
-- colour), a chamfered hex nut (three slabs ∩ two cones, minus its bore, plus the rings
-- of its thread), a copper pipe tee (two pipes and three collars, minus two bores) and a
-- chrome bowl on a foot (a sphere ∩ a box, plus a cylinder, minus a sphere) that mirrors
-- the others. A large warm area light overhead gives soft shadows; a small cool point
-- light at the right gives sharp ones.
-- Render it with:  glint render scenes/machined.lua

gr.transform_order('pre')

white  = gr.material({0.85, 0.85, 0.85}, {0.2, 0.2, 0.2}, 20)
dark   = gr.material({0.15, 0.15, 0.18}, {0.2, 0.2, 0.2}, 20)
ivory  = gr.material({0.9, 0.87, 0.78}, {0.5, 0.5, 0.5}, 60)
ink    = gr.material({0.05, 0.05, 0.08}, {0.3, 0.3, 0.3}, 40)
brass  = gr.material({0.6, 0.45, 0.12}, {0.7, 0.6, 0.3}, 80)
copper = gr.material({0.7, 0.3, 0.15}, {0.7, 0.45, 0.3}, 60)
chrome = gr.material('chrome')
chrome:set_diffuse(0.05, 0.05, 0.05)
chrome:set_specular(0.8, 0.8, 0.8)
chrome:set_shininess(400)
chrome:set_reflection(0.8, 0.8, 0.85)

root = gr.node('root')

-- The floor: 10×10 tiles, top at y = 0.
for i = 0, 9 do
  for j = 0, 9 do
    local tile = gr.cube('tile' .. i .. '_' .. j)
    tile:set_material(((i + j) % 2 == 0) and white or dark)
    tile:scale(1, 0.2, 1)
    tile:translate(i - 5, -0.2, j - 5)
    root:add_child(tile)
  end
end

-- The union of parts[lo..hi] as a balanced tree (shallower than a chain: at most 16
-- nested operations per CSG object).
local function union_all(name, parts, lo, hi)
  lo = lo or 1
  hi = hi or #parts
  if lo == hi then return parts[lo] end
  local mid = (lo + hi) // 2
  return gr.csg(name .. lo .. '-' .. hi, 'u',
                union_all(name, parts, lo, mid), union_all(name, parts, mid + 1, hi))
end

-- A cylinder of radius r from height y0 to y1, standing (gr.cylinder's axis is z).
local function upright(name, r, y0, y1)
  local c = gr.cylinder(name)
  c:scale(r, r, y1 - y0)
  c:rotate('x', -90)
  c:translate(0, y0, 0)
  return c
end

-- The die: [-1, 1]³ ∩ a sphere of radius 1.4 (rounded edges, a flat disc of radius 0.98
-- on each face), minus one dimple per pip: a sphere of radius 0.2 centred 0.06 outside
-- the face. Opposite faces sum to 7; 4, 5 and 6 face the camera.
local pips = {}
local function face(n, axis, sign, spots)
  for k, uv in ipairs(spots) do
    local s = 0.48
    local p = {0, 0, 0}
    local u_axis, v_axis = (axis % 3) + 1, ((axis + 1) % 3) + 1
    p[axis] = sign * 1.06
    p[u_axis] = uv[1] * s
    p[v_axis] = uv[2] * s
    local pip = gr.sphere('pip' .. n .. '_' .. k)
    pip:scale(0.2, 0.2, 0.2)
    pip:translate(p[1], p[2], p[3])
    pips[#pips + 1] = pip
  end
end
local centre = {{0, 0}}
local two    = {{-1, -1}, {1, 1}}
local three  = {{-1, -1}, {0, 0}, {1, 1}}
local four   = {{-1, -1}, {1, 1}, {-1, 1}, {1, -1}}
local five   = {{-1, -1}, {1, 1}, {-1, 1}, {1, -1}, {0, 0}}
local six    = {{-1, -1}, {-1, 0}, {-1, 1}, {1, -1}, {1, 0}, {1, 1}}
face(5, 2,  1, five)   -- +y (top)
face(2, 2, -1, two)    -- -y
face(4, 3,  1, four)   -- +z
face(3, 3, -1, three)  -- -z
face(6, 1, -1, six)    -- -x
face(1, 1,  1, centre) -- +x
local pip_holes = union_all('pips', pips)
pip_holes:set_material(ink)
local cube = gr.cube('die-cube')
cube:translate(-0.5, -0.5, -0.5)
cube:scale(2, 2, 2)
local ball = gr.sphere('die-ball')
ball:scale(1.4, 1.4, 1.4)
local die = gr.csg('die', 'd', gr.csg('rounded-cube', 'i', cube, ball), pip_holes)
die:set_material(ivory)
die:scale(0.55, 0.55, 0.55)
die:rotate('y', 35)
die:translate(-2.3, 0.553, -1.1)
root:add_child(die)

-- The nut: three slabs 1.6 thick turned 60° apart make a hexagonal prism 0.7 high; a
-- 45° cone at each end chamfers its corners; the bore (radius 0.45) goes through, and
-- four rings (tori) inside it stand for the thread.
local slabs = {}
for k = 0, 2 do
  local slab = gr.cube('slab' .. k)
  slab:translate(-0.5, 0, -0.5)
  slab:scale(1.6, 0.7, 4)
  slab:rotate('y', 60 * k)
  slabs[#slabs + 1] = slab
end
local hex = gr.csg('hex', 'i', gr.csg('hex01', 'i', slabs[1], slabs[2]), slabs[3])
local top_chamfer = gr.cone('top-chamfer', 0, 2)
top_chamfer:rotate('x', 90) -- apex up, opening downwards
top_chamfer:translate(0, 0.7 + 0.84, 0)
local bottom_chamfer = gr.cone('bottom-chamfer', 0, 2)
bottom_chamfer:rotate('x', -90) -- apex down, opening upwards
bottom_chamfer:translate(0, -0.84, 0)
local blank = gr.csg('blank', 'i', gr.csg('chamfered', 'i', hex, top_chamfer), bottom_chamfer)
local bored = gr.csg('bored', 'd', blank, upright('bore', 0.45, -0.3, 1.0))
local rings = {}
for k = 1, 4 do
  local ring = gr.torus('thread' .. k, 0.45, 0.05)
  ring:rotate('x', 90)
  ring:translate(0, 0.7 * k / 5, 0)
  rings[#rings + 1] = ring
end
local nut = gr.csg('nut', 'u', bored, union_all('thread', rings))
nut:set_material(brass)
nut:scale(0.85, 0.85, 0.85)
nut:rotate('y', 20)
nut:translate(1.9, 0.003, 1.2)
root:add_child(nut)

-- The pipe tee: a run along x and a branch upwards (radius 0.32), a collar (radius 0.4,
-- 0.18 long) on each of the three ends, minus the bores (radius 0.22), which run past
-- the ends so the pipe is open.
local function along_x(name, r, x0, x1)
  local c = gr.cylinder(name)
  c:scale(r, r, x1 - x0)
  c:rotate('y', 90)
  c:translate(x0, 0, 0)
  return c
end
local pipes = gr.csg('pipes', 'u', along_x('run', 0.32, -1, 1), upright('branch', 0.32, 0, 1))
local collars = gr.csg('collars', 'u',
                       gr.csg('run-collars', 'u', along_x('collar-l', 0.4, -1, -0.82),
                              along_x('collar-r', 0.4, 0.82, 1)),
                       upright('collar-up', 0.4, 0.82, 1))
local bores = gr.csg('bores', 'u', along_x('run-bore', 0.22, -1.2, 1.2),
                     upright('branch-bore', 0.22, 0, 1.2))
local tee = gr.csg('tee', 'd', gr.csg('tee-body', 'u', pipes, collars), bores)
tee:set_material(copper)
tee:rotate('y', -20)
tee:translate(-0.5, 0.403, 1.7)
root:add_child(tee)

-- The bowl: a sphere of radius 1 cut off at y = 0.3, on a foot (radius 0.4), hollowed
-- by a sphere of radius 0.92. Chrome: it mirrors the die, the tee and the floor.
local outer = gr.sphere('outer')
local cut = gr.cube('cut')
cut:translate(-0.5, 0, -0.5)
cut:scale(2.4, 1.4, 2.4)
cut:translate(0, -1.1, 0)
local inner = gr.sphere('inner')
inner:scale(0.92, 0.92, 0.92)
local shell = gr.csg('footed', 'u', gr.csg('cup', 'i', outer, cut), upright('foot', 0.4, -1.1, -0.9))
local bowl = gr.csg('bowl', 'd', shell, inner)
bowl:set_material(chrome)
bowl:scale(1.1, 1.1, 1.1)
bowl:translate(0.5, 1.1 * 1.1 + 0.003, -1.6)
root:add_child(bowl)

lights = {
  -- A 2.5×2 warm panel overhead, 3×3 shadow samples.
  gr.area_light({-1.5, 7, 2.5}, {2.5, 0, 0}, {0, 0, 2}, {0.8, 0.75, 0.65}, {1, 0, 0}, 3),
  -- A small cool point light at the right.
  gr.light({6, 4, 5}, {0.3, 0.32, 0.42}, {1, 0, 0}),
}

gr.render(root, 'machined.png', 400, 250,
          {0, 2.9, 6.4}, {0, -0.36, -1}, {0, 1, 0}, 40,
          {0.2, 0.2, 0.22}, lights)
