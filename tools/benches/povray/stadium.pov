// POV-Ray twin of tools/benches/scenes/stadium.lua: the same camera, geometry, lights,
// materials and random draws, z negated (POV-Ray is left-handed). A4 Phong: pigment kd, finish
// { ambient 1 diffuse 1 phong ks phong_size p } under ambient_light = the scene's ambient.
// Render: povray +Istadium.pov +W1024 +H768 -A +WT2 File_Gamma=1.0 +L<folder of Cow.inc>
// where Cow.inc is `obj2mesh2.py scenes/cs488/a4-2021plus/cow.obj Cow` (tools/benches/compare.sh
// does all of this).
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb <0.3, 0.3, 0.3> }
background { rgb <0.55, 0.7, 0.9> }

#macro A4(Kd, Ks, P)
  texture { pigment { rgb Kd } finish { ambient 1 diffuse 1 phong Ks phong_size P } }
#end

#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0, 2, -7>
  look_at <0, 2 - 0.15, -7 + 1>
  right x * Aspect
  up y
  angle 2 * degrees(atan(tan(radians(40 / 2)) * Aspect))
}

light_source { <300, 800, -600> rgb <0.9, 0.9, 0.9> }
light_source { <-400, 200, -300> rgb <0.3, 0.3, 0.35> }

// Park–Miller minimal standard generator, as in the Lua scene (exact in doubles).
#declare Seed = 20261129;
#macro Rand()
  #declare Seed = mod(Seed * 16807, 2147483647);
  (Seed / 2147483647)
#end

box { <-2000, -1, -2000>, <2000, 0, 2000> A4(<0.45, 0.55, 0.35>, 0.0, 1) }

#declare Paints = array[4] { <0.8, 0.2, 0.2>, <0.2, 0.3, 0.8>, <0.9, 0.8, 0.2>, <0.7, 0.7, 0.7> };
#declare Columns = 22;
#declare Rows = 20;
#for (J, 0, Rows - 1)
  #for (I, 0, Columns - 1)
    #declare X = -2000 + (I + Rand()) * 4000 / Columns;
    #declare Z = -2000 + (J + Rand()) * 4000 / Rows;
    #declare R = 10 + 30 * Rand();
    #if (X * X + Z * Z < 60 * 60)
      #declare X = X + 120;
    #end
    sphere { <X, R, -Z>, R A4(Paints[mod(I + J, 4)], 0.5, 25) }
  #end
#end

#include "Cow.inc"
object { Cow translate <0, 3.637, 0> scale 0.3 A4(<0.84, 0.6, 0.53>, 0.3, 20) }
