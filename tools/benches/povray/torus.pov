// POV-Ray twin of scenes/meshes/torus-povray.lua: the smooth torus of
// scenes/meshes/make_torus.py as smooth triangles (mesh2 with normal_vectors, from
// `obj2mesh2.py scenes/meshes/torus.obj Torus`), z negated (POV-Ray is left-handed), A4
// Phong: pigment kd, finish { ambient 1 diffuse 1 phong ks phong_size p } under
// ambient_light = the scene's ambient. Rendered by tools/benches/povray/torus-reference.sh into
// tests/golden/povray-torus.png, which tests/oracle/shading.rs compares glint's render with.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb <0.15, 0.15, 0.15> }
background { rgb <0.1, 0.1, 0.15> }

#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0, -3.4, -2.4>
  sky <0, 0, -1>
  right x * Aspect
  up y
  angle 2 * degrees(atan(tan(radians(30 / 2)) * Aspect))
  look_at <0, 0, 0>
}

#include "Torus.inc"
// gr.rotate('x', -20) mirrored in z: a rotation about x by +20 degrees.
object {
  Torus
  texture { pigment { rgb <0.8, 0.45, 0.25> } finish { ambient 1 diffuse 1 phong 0.6 phong_size 30 } }
  rotate <20, 0, 0>
}

light_source { <-3, -4, -5> rgb <0.9, 0.9, 0.9> }
light_source { <4, 1, -1> rgb <0.3, 0.4, 0.6> }
