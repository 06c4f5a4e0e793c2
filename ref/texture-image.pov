// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W128 +H96 +FE +A0.0 +AM2 +R5 -J
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 1
  adc_bailout 0
}
camera {
  perspective
  location <0.3, 1.2, 4>
  direction <-0.09843159, -0.3937263, -1.312421>
  right <1.329599, 0, -0.09971994>
  up <-0.0214355, 0.9580476, -0.2858067>
}
// material 'wall'
#declare T1 = texture { pigment { image_map { png "tests/pov/texture-image.png" gamma srgb interpolate 2 } } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T2 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <1, 2, 3> color rgb <1909859, 1909859, 1909859> fade_distance 0.001 fade_power 2 }
polygon { 5, <-2, -1, 0>, <2, -1, 0>, <2, 1.2, 0>, <-2, 1.2, 0>, <-2, -1, 0> texture { T1 translate <-0.25, 0, -0.5> scale <0.5, 1, 1> matrix <4, 0, 0, 0, 2.2, 0, 0, 0, 1, -2, -1, 0> } }
polygon { 5, <-4, -1, 4>, <4, -1, 4>, <4, -1, -4>, <-4, -1, -4>, <-4, -1, 4> texture { T2 } }
