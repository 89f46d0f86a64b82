-- Smooth meshes: vertex normals interpolated across each triangle. Left to right: the
-- torus of meshes/torus.obj (OBJ `vn`) faceted, as glint drew it before (the same file
-- through `readobj`, which keeps positions and faces only), the same torus smooth, a
-- mirror torus standing on edge (smooth: the reflection bends with the normals), and in
-- front a coarse sphere built here with inline per-vertex normals and UVs, smooth and
-- bump-mapped on top.
-- Render it with:  glint render scenes/smooth.lua   (--shading flat: every mesh faceted)

gr.transform_order('pre')

copper = gr.material({0.8, 0.45, 0.25}, {0.6, 0.6, 0.6}, 30)
jade = gr.material({0.25, 0.6, 0.4}, {0.5, 0.5, 0.5}, 40)
mirror = gr.material('mirror')
mirror:set_diffuse(0.05, 0.05, 0.05)
mirror:set_specular(0.7, 0.7, 0.7)
mirror:set_shininess(200)
mirror:set_reflection(0.8, 0.8, 0.85)
bumpy = gr.material('bumpy')
bumpy:set_diffuse(0.7, 0.3, 0.5)
bumpy:set_specular(0.5, 0.5, 0.5)
bumpy:set_shininess(50)
bumpy:set_bump('../textures/bumps.png', 0.01)
floor_material = gr.material({0.75, 0.75, 0.7}, {0.1, 0.1, 0.1}, 10)

root = gr.node('root')

floor = gr.cube('floor')
floor:set_material(floor_material)
floor:scale(12, 0.2, 8)
floor:translate(-6, -0.2, -5)
root:add_child(floor)

-- The torus lies in its own xy plane: stand it on the floor, tube radius 0.4.
local function place(node, x, z, turn)
  node:rotate('x', 90)
  node:rotate('y', turn)
  node:translate(x, 0.4, z)
  root:add_child(node)
end

flat = gr.mesh('flat-torus', readobj('meshes/torus.obj'))
flat:set_material(copper)
place(flat, -2.7, -0.2, 0)

smooth = gr.mesh('smooth-torus', 'meshes/torus.obj')
smooth:set_material(jade)
place(smooth, -0.3, 0.3, 0)

ring = gr.mesh('mirror-torus', 'meshes/torus.obj')
ring:set_material(mirror)
ring:rotate('y', -35)
ring:translate(2.9, 1.4, -1.4)
root:add_child(ring)

-- A 16 × 8 UV sphere: normals are the unit positions, u around, v from pole to pole.
local verts, faces, uvs, normals = {}, {}, {}, {}
local around, down = 16, 8
for j = 0, down do
  local lat = math.pi * (j / down - 0.5)
  for i = 0, around do
    local lon = 2 * math.pi * i / around
    local n = {math.cos(lat) * math.cos(lon), math.sin(lat), -math.cos(lat) * math.sin(lon)}
    verts[#verts + 1] = n
    normals[#normals + 1] = n
    uvs[#uvs + 1] = {2 * i / around, j / down}
  end
end
for j = 0, down - 1 do
  for i = 0, around - 1 do
    local a = j * (around + 1) + i
    local b = a + around + 1
    faces[#faces + 1] = {a, a + 1, b + 1, b}
  end
end
ball = gr.mesh('bumpy-ball', verts, faces, uvs, normals)
ball:set_material(bumpy)
ball:scale(0.7, 0.7, 0.7)
ball:translate(1.9, 0.7, 1.5)
root:add_child(ball)

lights = {
  gr.light({-5, 8, 7}, {0.8, 0.8, 0.75}, {1, 0, 0}),
  gr.light({6, 4, 5}, {0.3, 0.35, 0.5}, {1, 0, 0}),
}

gr.render(root, 'smooth.png', 480, 270,
          {0, 2.6, 7.5}, {0, -0.3, -1}, {0, 1, 0}, 40,
          {0.25, 0.25, 0.3}, lights)
