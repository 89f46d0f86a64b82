-- glint's CSG scene: a glass made of cylinders minus a cylinder (the inside is cut with
-- its top cap coplanar with the outside's) with a torus rim, the classic
-- "sphere ∩ cube minus three cylinders" on a pedestal, a lens (sphere ∩ sphere), and a
-- ring, a cone and a cylinder beside them, on a checkerboard floor.
-- Render it with:  glint render scenes/csg.lua

gr.transform_order('pre')

white  = gr.material({0.85, 0.85, 0.85}, {0.2, 0.2, 0.2}, 20)
dark   = gr.material({0.15, 0.15, 0.18}, {0.2, 0.2, 0.2}, 20)
glass  = gr.material({0, 0, 0}, {0.9, 0.9, 0.9}, 120)
glass:set_refraction(1.5)
blue   = gr.material({0.15, 0.3, 0.8}, {0.6, 0.6, 0.6}, 60)
red    = gr.material({0.8, 0.15, 0.1}, {0.6, 0.6, 0.6}, 60)
gold   = gr.material({0.6, 0.45, 0.1}, {0.7, 0.6, 0.3}, 80)
green  = gr.material({0.15, 0.65, 0.25}, {0.5, 0.5, 0.5}, 40)
stone  = gr.material({0.55, 0.5, 0.45}, {0.1, 0.1, 0.1}, 10)

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

-- A cylinder of radius r from height y0 to y1, standing (gr.cylinder's axis is z).
local function upright(name, r, y0, y1)
  local c = gr.cylinder(name)
  c:scale(r, r, y1 - y0)
  c:rotate('x', -90)
  c:translate(0, y0, 0)
  return c
end

-- The glass: a tumbler of clear glass (index 1.5): a thick base and a bowl (cylinders)
-- minus the inside (a cylinder whose top cap is coplanar with the wall's), plus a torus
-- rim. No stem: a thin glass rod or disk is a light guide whose chains of total internal
-- reflection outlast max_depth and end in black pixels (see tests/refraction.rs). It
-- stands a hair above the floor: a glass face coplanar with the tiles' tops would leave
-- each ray to rounding to decide which of the two it meets first.
local base = upright('base', 0.6, 0.0, 0.35)
local bowl = upright('bowl', 0.6, 0.3, 1.5)
local hollow = upright('hollow', 0.54, 0.35, 1.5)
local cup = gr.csg('cup', 'd', gr.csg('body', 'u', base, bowl), hollow)
local rim = gr.torus('rim', 0.57, 0.03)
rim:rotate('x', -90)
rim:translate(0, 1.5, 0)
local glass_node = gr.csg('glass', 'u', cup, rim)
glass_node:set_material(glass)
glass_node:translate(-2.0, 0.003, 0.3)
root:add_child(glass_node)

-- The classic: a sphere ∩ a cube, minus three crossing cylinders (the holes keep the
-- cylinders' red), on a stone pedestal.
local ball = gr.sphere('ball')
ball:scale(1.3, 1.3, 1.3)
local box = gr.cube('box')
box:translate(-0.5, -0.5, -0.5)
box:scale(2, 2, 2)
local function drill(name, axis)
  local c = gr.cylinder(name)
  c:translate(0, 0, -0.5)
  c:scale(0.55, 0.55, 3)
  if axis == 'x' then c:rotate('y', 90) elseif axis == 'y' then c:rotate('x', 90) end
  return c
end
local drills = gr.csg('drills', 'u', gr.csg('drills-xy', 'u', drill('dx', 'x'), drill('dy', 'y')),
                      drill('dz', 'z'))
drills:set_material(red)
local classic = gr.csg('classic', 'd', gr.csg('rounded-box', 'i', ball, box), drills)
classic:set_material(blue)
classic:scale(0.7, 0.7, 0.7)
classic:rotate('y', 35)
classic:rotate('x', 25)
classic:translate(0.2, 1.45, -0.6)
root:add_child(classic)
local pedestal = upright('pedestal', 0.5, 0.0, 0.55)
pedestal:set_material(stone)
pedestal:translate(0.2, 0, -0.6)
root:add_child(pedestal)

-- A lens: the intersection of two spheres.
local s1 = gr.sphere('s1')
s1:translate(0, 0, -0.8)
local s2 = gr.sphere('s2')
s2:translate(0, 0, 0.8)
local lens = gr.csg('lens', 'i', s1, s2)
lens:set_material(gold)
lens:scale(1.1, 1.1, 1.1)
lens:rotate('y', -70)
lens:translate(2.2, 0.66, -0.5)
root:add_child(lens)

-- A ring, a cone and a cylinder.
local ring = gr.torus('ring', 0.45, 0.12)
ring:set_material(green)
ring:rotate('x', 90)
ring:translate(1.3, 0.12, 1.5)
root:add_child(ring)
local cone = gr.cone('cone', 0, 1)
cone:set_material(red)
cone:scale(0.35, 0.35, 0.9)
cone:rotate('x', 90)
cone:translate(-0.6, 0.9, 1.6)
root:add_child(cone)
local post = upright('post', 0.2, 0.0, 1.1)
post:set_material(gold)
post:translate(2.7, 0, 1.3)
root:add_child(post)

gr.render(root, 'csg.png', 640, 400,
  {0, 2.6, 6.2}, {0, -1.7, -6.2}, {0, 1, 0}, 42,
  {0.25, 0.25, 0.28},
  {gr.light({-4, 7, 5}, {0.85, 0.85, 0.8}, {1, 0, 0}),
   gr.light({5, 4, 3}, {0.3, 0.3, 0.35}, {1, 0, 0})})
