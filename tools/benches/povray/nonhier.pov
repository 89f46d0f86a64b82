// POV-Ray twin of scenes/cs488/a4-2021plus/nonhier.lua (spheres, a box, a stellated
// dodecahedron mesh), z negated (POV-Ray is left-handed), rendered at 1024×768 without
// anti-aliasing beside `glint render --width 1024 --height 768 --aa none`. A4 Phong:
// pigment kd, finish { ambient 1 diffuse 1 phong ks phong_size p } under ambient_light =
// the scene's ambient; POV-Ray's highlight is white, so a coloured ks becomes its mean.
// Render: povray +Inonhier.pov +W1024 +H768 -A +WT2 File_Gamma=1.0 +L<folder of Dodec.inc>
// where Dodec.inc is `obj2mesh2.py scenes/cs488/a4-2021plus/smstdodeca.obj Dodec`.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb <0.3, 0.3, 0.3> }
background { rgb <0.5, 0.5, 0.5> }

#macro A4(Kd, Ks, P)
  texture { pigment { rgb Kd } finish { ambient 1 diffuse 1 phong (Ks.x + Ks.y + Ks.z) / 3 phong_size P } }
#end

#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0, 0, -800>
  look_at <0, 0, 0>
  right x * Aspect
  up y
  angle 2 * degrees(atan(tan(radians(50 / 2)) * Aspect))
}

#declare Mat1 = A4(<0.7, 1.0, 0.7>, <0.5, 0.7, 0.5>, 25)
#declare Mat2 = A4(<0.5, 0.5, 0.5>, <0.5, 0.7, 0.5>, 25)
#declare Mat3 = A4(<1.0, 0.6, 0.1>, <0.5, 0.7, 0.5>, 25)
#declare Mat4 = A4(<0.7, 0.6, 1.0>, <0.5, 0.4, 0.8>, 25)

sphere { <0, 0, 400>, 100 texture { Mat1 } }
sphere { <200, 50, 100>, 150 texture { Mat1 } }
sphere { <0, -1200, 500>, 1000 texture { Mat2 } }
box { <-200, -225, -100>, <-100, -125, -200> texture { Mat4 } }
sphere { <-150, -85, -150>, 30 texture { Mat3 } }
sphere { <0, 100, 250>, 25 texture { Mat1 } }

#include "Dodec.inc"
object { Dodec texture { Mat3 } }

light_source { <-100, 150, -400> rgb <0.9, 0.9, 0.9> }
light_source { <400, 100, -150> rgb <0.7, 0.0, 0.7> }
