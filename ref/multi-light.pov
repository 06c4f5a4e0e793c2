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
  location <0, 2.5, 6>
  direction <0, -0.4119007, -1.235702>
  right <1.333333, 0, 0>
  up <0, 0.9486833, -0.3162278>
}
// material 'floor'
#declare T1 = texture { pigment { rgb <0.6, 0.6, 0.6> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'ball'
#declare T2 = texture { pigment { rgb <0.8, 0.8, 0.8> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'box'
#declare T3 = texture { pigment { rgb <0.5, 0.6, 0.4> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <-3, 3, 2> color rgb <1273240, 318309.9, 159154.9> fade_distance 0.001 fade_power 2 }
light_source { <3, 2.5, 1> color rgb <159154.9, 477464.8, 1273240> fade_distance 0.001 fade_power 2 }
light_source { <1.5, 2.2, 1.5> color rgb <192000, 192000, 256000>
  fade_distance 0.001 fade_power 2
  area_light <0.15, 0, 0>, <0, 0.15, 0>, 16, 16 circular orient jitter area_illumination on
  looks_like { sphere { 0, 0.08 pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission rgb <60, 60, 80> } no_radiosity } } }
polygon { 5, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6>, <-6, 0, 6> texture { T1 } }
polygon { 5, <-1.3, 1, 0.5>, <-0.0999999, 1, 0.5>, <-0.0999999, 0.8, -0.5>, <-1.3, 0.8, -0.5>, <-1.3, 1, 0.5> texture { T2 } }
polygon { 5, <0.4, 0, -0.8>, <1.3, 0, -0.6>, <1.3, 1, -0.6>, <0.4, 1, -0.8>, <0.4, 0, -0.8> texture { T3 } }
light_source { <0, 3.5, -1> color rgb <477464.8, 477464.8, 397887.4>
  fade_distance 0.001 fade_power 2
  spotlight point_at <0, 2.5, -1> radius 90 falloff 90 tightness 1
  area_light <0.9375, 0, 0>, <0, 0, 0.9375>, 16, 16 jitter area_illumination on
  looks_like { polygon { 5, <-0.5, 0, -0.5>, <0.5, 0, -0.5>, <0.5, 0, 0.5>, <-0.5, 0, 0.5>, <-0.5, 0, -0.5> pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission rgb <3, 3, 2.5> } no_radiosity } } }
