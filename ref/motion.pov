// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W128 +H96 +FE +A0.0 +AM2 +R5 -J +KFI1 +KFF64 +KI0.0078125 +KF0.9921875
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 1
  adc_bailout 0
}
// Scene time: the shutter [0, 1] spanned by the clock in [0, 1].
#declare MC_T = 0 + clock*1;
camera {
  perspective
  location <0, 2, 6>
  direction <0, -0.3331806, -1.332722>
  right <1.333333, 0, 0>
  up <0, 0.9701424, -0.2425356>
}
// material 'red'
#declare T2 = texture { pigment { rgb <0.8, 0.2, 0.1> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'blue'
#declare T3 = texture { pigment { rgb <0.2, 0.3, 0.8> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T1 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <1, 5, 3> color rgb <3978874, 3978874, 3978874> fade_distance 0.001 fade_power 2 }
sphere { <-1.3, 0.8, 0.5>, 0.45 texture { T2 } translate MC_T*<1.6, 0, 0> }
sphere { <0.8, 0.4, -1>, 0.4 texture { T3 } }
polygon { 5, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6>, <-6, 0, 6> texture { T1 } }
