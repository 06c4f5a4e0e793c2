// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W96 +H96 +FE +A0.0 +AM2 +R5 -J
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 1
  adc_bailout 0
}
camera {
  perspective
  location <0, 0.8, 6>
  direction <0, -0.06860124, -1.372025>
  right <1, 0, 0>
  up <0, 0.9987524, -0.04993762>
  aperture 0.48
  focal_point <0, 0.7001247, 4.002495>
  blur_samples 100, 100
  confidence 0.9999
  variance 0
}
// material 'near'
#declare T2 = texture { pigment { rgb <0.8, 0.2, 0.1> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'mid'
#declare T3 = texture { pigment { rgb <0.9, 0.9, 0.9> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'far'
#declare T4 = texture { pigment { rgb <0.1, 0.3, 0.8> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T1 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <2, 5, 5> color rgb <6366198, 6366198, 6366198> fade_distance 0.001 fade_power 2 }
sphere { <-0.9, 0.4, 2.5>, 0.4 texture { T2 } }
sphere { <0, 0.5, 0>, 0.5 texture { T3 } }
sphere { <1.2, 0.6, -4>, 0.6 texture { T4 } }
polygon { 5, <-6, 0, 8>, <6, 0, 8>, <6, 0, -8>, <-6, 0, -8>, <-6, 0, 8> texture { T1 } }
