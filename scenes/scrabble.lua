-- glint's showcase: a game of Scrabble on a wooden table, with a mirror behind the board
-- and a clear glass of water beside it (the proposal's final scene).
--
-- One unit is one board square. The table's top is y = 0; the board lies on it centred
-- on the origin, row 1 at the far side (z = -7) and row 15 nearest the camera (z = +7).
-- Every texture comes from tools/examples/make_textures.rs (cargo run --example make_textures):
-- the board (premium squares, labels) with a groove between squares in its bump map; one
-- atlas of tile faces (letter and value per cell, engraved in its bump map); and wood,
-- with a matching bump map, for the table, the racks and the mirror's frame.
-- Render it with:  glint render scenes/scrabble.lua      (docs/scrabble.md explains it)

gr.transform_order('pre')

-- The game: 45 tiles spelling crossing words (every run of two or more letters is a
-- word), the first word over the centre star, and two racks.
local board_rows = {
  '...............',
  '.....F.........',
  '.....L.........',
  '....RAY........',
  '.....S.........',
  '..LIGHT........',
  '..E.A.O.W......',
  '..N.MIRROR.....',
  '..S.E.U.R......',
  '......S.D......',
  '........SHADOW.',
  '..........N..A.',
  '..........G..V.',
  '..........L..E.',
  '......PRIZE....',
}
local near_rack = 'GLINTJX'
local far_rack = 'BOUQUET'

-- Materials. Texels are used as stored; the bump strengths are heights per unit of
-- texture space, chosen so the grooves, engraving and grain catch the light.
local board_material = gr.material('board')
board_material:set_diffuse('../textures/scrabble-board.png')
board_material:set_specular(0.12, 0.12, 0.12)
board_material:set_shininess(30)
board_material:set_bump('../textures/scrabble-board-height.png', 0.0025)

local tile_material = gr.material('tile')
tile_material:set_diffuse('../textures/scrabble-tiles.png')
tile_material:set_specular(0.3, 0.3, 0.28)
tile_material:set_shininess(60)
tile_material:set_bump('../textures/scrabble-tiles-height.png', 0.0015)

local wood = gr.material('wood')
wood:set_diffuse('../textures/wood.png')
wood:set_specular(0.2, 0.18, 0.15)
wood:set_shininess(25)
wood:set_bump('../textures/wood-height.png', 0.002)

local mirror_material = gr.material({0.02, 0.02, 0.02}, {0.8, 0.8, 0.8}, 2000)
mirror_material:set_reflection(0.88)

local glass = gr.material('glass')
glass:set_diffuse(0, 0, 0)
glass:set_specular(0.7, 0.7, 0.7)
glass:set_shininess(400)
glass:set_refraction(1.5)

local water = gr.material('water')
water:set_diffuse(0, 0, 0)
water:set_specular(0.5, 0.5, 0.5)
water:set_shininess(200)
water:set_refraction(1.33)

local wall = gr.material({0.55, 0.52, 0.48}, {0, 0, 0}, 1)
local gilt = gr.material({0.45, 0.33, 0.1}, {0.75, 0.6, 0.3}, 60)

-- A block from (x0, y0, z0) to (x1, y1, z1) as an inline mesh with UVs: the top face
-- shows the texture rectangle top = {u0, v0, u1, v1} (v0 along the near edge, +z, so it
-- reads upright from the front), every other face the rectangle side. With bevel > 0
-- the top edges are chamfered by that much (the bevels show side). Faces wind
-- counter-clockwise seen from outside.
local function block(name, x0, y0, z0, x1, y1, z1, top, side, bevel)
  local verts, faces, uvs = {}, {}, {}
  local function quad(a, b, c, d, rect)
    local n = #verts
    for _, p in ipairs({a, b, c, d}) do verts[#verts + 1] = p end
    uvs[#uvs + 1] = {rect[1], rect[2]}
    uvs[#uvs + 1] = {rect[3], rect[2]}
    uvs[#uvs + 1] = {rect[3], rect[4]}
    uvs[#uvs + 1] = {rect[1], rect[4]}
    faces[#faces + 1] = {n, n + 1, n + 2, n + 3}
  end
  local b = bevel or 0
  local ys = y1 - b
  quad({x0 + b, y1, z1 - b}, {x1 - b, y1, z1 - b}, {x1 - b, y1, z0 + b}, {x0 + b, y1, z0 + b}, top)
  quad({x0, y0, z1}, {x1, y0, z1}, {x1, ys, z1}, {x0, ys, z1}, side)
  quad({x1, y0, z0}, {x0, y0, z0}, {x0, ys, z0}, {x1, ys, z0}, side)
  quad({x1, y0, z1}, {x1, y0, z0}, {x1, ys, z0}, {x1, ys, z1}, side)
  quad({x0, y0, z0}, {x0, y0, z1}, {x0, ys, z1}, {x0, ys, z0}, side)
  quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, side)
  if b > 0 then
    quad({x0, ys, z1}, {x1, ys, z1}, {x1 - b, y1, z1 - b}, {x0 + b, y1, z1 - b}, side)
    quad({x1, ys, z0}, {x0, ys, z0}, {x0 + b, y1, z0 + b}, {x1 - b, y1, z0 + b}, side)
    quad({x1, ys, z1}, {x1, ys, z0}, {x1 - b, y1, z0 + b}, {x1 - b, y1, z1 - b}, side)
    quad({x0, ys, z0}, {x0, ys, z1}, {x0 + b, y1, z1 - b}, {x0 + b, y1, z0 + b}, side)
  end
  return gr.mesh(name, verts, faces, uvs)
end

local root = gr.node('root')

-- The table: a wooden top (the wood repeats every 20 units) and a wall far behind.
local table_top = block('table', -40, -1, -30, 40, 0, 30, {0, 0, 4, 3}, {0, 0, 0.1, 0.1})
table_top:set_material(wood)
root:add_child(table_top)
local back_wall = gr.cube('wall')
back_wall:set_material(wall)
back_wall:scale(80, 40, 1)
back_wall:translate(-40, -1, -31)
root:add_child(back_wall)

-- The board: 16 × 16 × 0.25; its texture's 32-texel frame (of 1024) is half a square.
-- The sides show a patch of the frame.
local board = block('board', -8, 0, -8, 8, 0.25, 8, {0, 0, 1, 1}, {0.005, 0.5, 0.02, 0.51})
board:set_material(board_material)
root:add_child(board)

-- Tiles: 0.92 × 0.92 × 0.2 with chamfered top edges, one mesh per letter (its top face
-- on the letter's atlas cell: 6 × 6 cells, A = 0 … Z = 25 row by row from the top; the
-- sides on the blank cell 26), instanced wherever the letter is played.
local TILE, TILE_HEIGHT = 0.92, 0.2
local function cell_rect(k, margin)
  local column, row = k % 6, k // 6
  local m = margin / 768
  return {column / 6 + m, 1 - (row + 1) / 6 + m, (column + 1) / 6 - m, 1 - row / 6 - m}
end
local letter_meshes = {}
local function letter_mesh(letter)
  if not letter_meshes[letter] then
    local k = string.byte(letter) - string.byte('A')
    local h = TILE / 2
    local mesh = block('tile-' .. letter, -h, 0, -h, h, TILE_HEIGHT, h, cell_rect(k, 2),
                       cell_rect(26, 40), 0.035)
    mesh:set_material(tile_material)
    letter_meshes[letter] = mesh
  end
  return letter_meshes[letter]
end

-- A small, fixed wobble per tile (integer hash: the same on every run), so the tiles
-- sit a little unevenly in their squares, as played tiles do.
local function wobble(i, j, salt)
  return ((i * 7919 + j * 104729 + salt * 1299709) % 1001) / 1000 - 0.5
end

for row = 1, 15 do
  for column = 1, 15 do
    local letter = board_rows[row]:sub(column, column)
    if letter ~= '.' then
      local tile = gr.node('board-tile-' .. row .. '-' .. column)
      tile:add_child(letter_mesh(letter))
      tile:rotate('y', 3 * wobble(row, column, 1))
      tile:translate(column - 8 + 0.05 * wobble(row, column, 2), 0.25,
                     row - 8 + 0.05 * wobble(row, column, 3))
      root:add_child(tile)
    end
  end
end

-- A rack: a wooden base, a front lip and a backrest, with its tiles leaning back at 70°
-- on the base (their faces to the player, at +z in the rack's frame).
local function rack(name, letters)
  local node = gr.node(name)
  local w = 4.3
  local parts = {
    block(name .. '-base', -w, 0, -0.8, w, 0.12, 0.75, {0, 0, 0.3, 0.05}, {0, 0, 0.3, 0.02}),
    block(name .. '-lip', -w, 0.12, 0.5, w, 0.22, 0.75, {0, 0, 0.3, 0.02}, {0, 0, 0.3, 0.02}),
    block(name .. '-back', -w, 0.12, -0.8, w, 0.75, 0.0, {0, 0, 0.3, 0.02}, {0, 0, 0.3, 0.02}),
  }
  for _, part in ipairs(parts) do
    part:set_material(wood)
    node:add_child(part)
  end
  local lean = 70
  for k = 1, #letters do
    local tile = gr.node(name .. '-tile-' .. k)
    tile:add_child(letter_mesh(letters:sub(k, k)))
    tile:rotate('x', lean)
    -- Lowest corner (near edge of the face side) onto the base, just behind the lip.
    local drop = (TILE / 2) * math.sin(math.rad(lean))
    tile:translate((k - 4) * 1.02, 0.12 + drop, 0.5 - (TILE / 2) * math.cos(math.rad(lean)) - 0.22)
    node:add_child(tile)
  end
  return node
end

local near = rack('near-rack', near_rack)
near:translate(-2.5, 0, 9.2)
root:add_child(near)
local far = rack('far-rack', far_rack)
far:rotate('y', 180)
far:translate(-3.5, 0, -9.3)
root:add_child(far)

-- The mirror: a pane in a gilt frame behind the board, leaning back a little, so that
-- from the camera it shows the board, the tiles and the far rack from the other side
-- (a mirror leaning towards the board would show only the squares next to it).
local mirror = gr.node('mirror')
local pane = gr.cube('pane')
pane:set_material(mirror_material)
pane:scale(17, 5.5, 0.1)
pane:translate(-8.5, 0.6, -0.05)
mirror:add_child(pane)
-- Frame bars: gilt boxes lying along x; the side bars turned upright.
local function bar(name, length, x, y, upright)
  local b = gr.cube(name)
  b:scale(length, 0.6, 0.35)
  b:translate(0, 0, -0.2)
  b:set_material(gilt)
  if upright then b:rotate('z', 90) end
  b:translate(x, y, 0)
  return b
end
mirror:add_child(bar('frame-bottom', 18.2, -9.1, 0, false))
mirror:add_child(bar('frame-top', 18.2, -9.1, 6.1, false))
mirror:add_child(bar('frame-left', 5.5, -8.5, 0.6, true))
mirror:add_child(bar('frame-right', 5.5, 9.1, 0.6, true))
mirror:rotate('x', -4)
mirror:translate(0, 0.001, -11.3)
root:add_child(mirror)

-- The glass: a tumbler made by CSG (a thick base and a wall, minus the inside, with a
-- torus rounding the rim), standing a hair above the table (coplanar glass and wood
-- would leave rounding to pick the surface), and water in it, a little narrower than the
-- inside so that the two dielectrics nest rather than touch.
local function upright(name, r, y0, y1)
  local c = gr.cylinder(name)
  c:scale(r, r, y1 - y0)
  c:rotate('x', -90)
  c:translate(0, y0, 0)
  return c
end
local R, HEIGHT, WALL = 1.6, 5.0, 0.12
local cup = gr.csg('cup', 'd',
  gr.csg('body', 'u', upright('base', R, 0, 0.5), upright('wall', R, 0.45, HEIGHT)),
  upright('inside', R - WALL, 0.5, HEIGHT))
local rim = gr.torus('rim', R - WALL / 2, WALL / 2)
rim:rotate('x', -90)
rim:translate(0, HEIGHT, 0)
local tumbler = gr.csg('tumbler', 'u', cup, rim)
tumbler:set_material(glass)
tumbler:translate(10.7, 0.003, 5.8)
root:add_child(tumbler)
local water_column = upright('water', R - WALL - 0.01, 0.51, 3.2)
water_column:set_material(water)
water_column:translate(10.7, 0.003, 5.8)
root:add_child(water_column)

-- Light: a soft lamp above the player's left (an area light: soft shadows) and a dim
-- fill from the right.
local lamp = gr.area_light({-9, 26, 16}, {6, 0, 0}, {0, 0, 6}, {0.78, 0.75, 0.68}, {1, 0, 0}, 4)
local fill = gr.light({16, 14, 10}, {0.22, 0.22, 0.26}, {1, 0, 0})

gr.render(root, 'scrabble.png', 1280, 720,
  {0, 17.5, 19}, {0, -17.5, -19.6}, {0, 1, 0}, 48,
  {0.3, 0.3, 0.3}, {lamp, fill},
  {aa = 'adaptive', max_depth = 8})
