-- Dialect prelude: textures and bump maps the way many CS488 tracers wrote them.
--
--   glint render scene.lua --prelude scenes/dialects/textures.lua
--
-- The meaning assumed (glint's own calls in brackets):
--
-- m:set_texture(file)              the image replaces the material's diffuse colour kd
--                                  [m:set_diffuse(file)].
-- m:set_bumpmap(file[, strength])  a height map (grey levels: light is high) that tilts
--                                  the normal [m:set_bump(file, strength)], strength 1 by
--                                  default. Scenes whose tracer read a normal map (an RGB
--                                  image of normals, mostly blue) get a wrong relief.
-- gr.texture(file[, ...])          a texture value for the calls below; other arguments
--                                  (repeat counts, flags) are ignored.
-- node:set_texture(tex or file)    the node's surface takes the image as its diffuse
-- node:set_bumpmap(file[, strength]) colour (or relief); the rest of the node's material
--                                  stays. Glint keeps textures on materials, so the node
--                                  gets its own copy of its material [m:copy()], one per
--                                  material and texture (nodes that share both share the
--                                  copy); set_material and set_texture may come in either
--                                  order. A node without a material gets glint's default
--                                  (kd 0.5 grey) under the texture.
-- gr.image_material(file, {su, sv}, ks, p, ...)  a material whose diffuse colour is the
-- gr.image_material(file, ks, p, ...)            image, with specular ks and shininess p
--                                  (defaults {0,0,0} and 0); the repeat counts {su, sv} are
--                                  ignored (glint has no texture scale: the image covers
--                                  each surface once, in glint's UVs) and so are flags
--                                  after p.
--
-- Images are read relative to the scene's folder, as glint reads them. The UVs are
-- glint's (docs/scene-language.md, "UV conventions"); another tracer may have laid the
-- same image differently on a sphere or a cube.

local function file_of(call, n, tex)
  if type(tex) == 'string' then return tex end
  if type(tex) == 'table' and type(tex.file) == 'string' then return tex.file end
  error(string.format('%s: argument %d (texture) must be a file name or a texture made by '
    .. 'gr.texture, got %s', call, n, type(tex)), 3)
end

function gr.texture(file)
  if type(file) ~= 'string' then
    error('gr.texture: argument 1 (file) must be the file name of an image, got '
      .. type(file), 2)
  end
  return {file = file}
end

gr.extend_material('set_texture', function(m, tex)
  return m:set_diffuse(file_of('material:set_texture', 1, tex))
end)

gr.extend_material('set_bumpmap', function(m, file, strength)
  return m:set_bump(file_of('material:set_bumpmap', 1, file), strength)
end)

function gr.image_material(file, a, b, c)
  file = file_of('gr.image_material', 1, file)
  local ks, p = a, b
  if type(a) == 'table' and #a == 2 then ks, p = b, c end
  -- kd does not matter: the image replaces it.
  local m = gr.material({1, 1, 1}, ks or {0, 0, 0}, p or 0)
  m:set_diffuse(file)
  return m
end

-- Per node: the material the scene gave it, and the maps it asked for.
local given = setmetatable({}, {__mode = 'k'})
local maps = setmetatable({}, {__mode = 'k'})
-- Per material (false: none): the copies made, by their maps' key.
local copies = setmetatable({}, {__mode = 'k'})
local default_key = {}

local set_material

-- The node's material with its maps applied: a shared copy per material and maps.
local function textured(node)
  local m, wants = given[node], maps[node]
  local key = (wants.diffuse or '') .. '\0' .. (wants.bump or '') .. '\0'
    .. tostring(wants.strength)
  local per = copies[m or default_key]
  if per == nil then
    per = {}
    copies[m or default_key] = per
  end
  if per[key] == nil then
    local copy = m and m:copy() or gr.material('textured')
    if wants.diffuse then copy:set_diffuse(wants.diffuse) end
    if wants.bump then copy:set_bump(wants.bump, wants.strength) end
    per[key] = copy
  end
  return per[key]
end

set_material = gr.extend_node('set_material', function(node, m)
  set_material(node, m) -- glint's own checks, and the node's material without maps
  given[node] = m
  if maps[node] == nil then return node end
  return set_material(node, textured(node))
end)

local function add_map(node, field, file, strength)
  maps[node] = maps[node] or {}
  maps[node][field] = file
  if field == 'bump' then maps[node].strength = strength end
  return set_material(node, textured(node))
end

gr.extend_node('set_texture', function(node, tex)
  return add_map(node, 'diffuse', file_of('node:set_texture', 1, tex))
end)

gr.extend_node('set_bumpmap', function(node, file, strength)
  return add_map(node, 'bump', file_of('node:set_bumpmap', 1, file), strength)
end)
