-- Dialect prelude: every call of the other preludes here that adds to glint's language
-- (materials, textures, planes, lights, csg, nh-shapes), for a scene that mixes them.
--
--   glint render scene.lua --prelude scenes/dialects/all.lua
--
-- Each file's header says the meaning it assumes. y-cylinders.lua is left out: it changes
-- what glint's own gr.cylinder means, so add it by name when the scene's cylinders stand
-- on y (--prelude scenes/dialects/all.lua --prelude scenes/dialects/y-cylinders.lua).
-- A prelude's require finds the files beside it, and a file runs once however it is
-- reached.

require('materials')
require('textures')
require('planes')
require('lights')
require('csg')
require('nh-shapes')
