// whitted-1980.pov -- Whitted's picture for POV-Ray 3.7: a red and yellow checkerboard
// under a mirror sphere and a glass sphere. The same scene as
// lessons/examples/whitted-1980.yaml (benches/peers/whitted_1980.py renders both and
// compares the checker cells).
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 1/255
  ambient_light rgb 1
}
camera {
  perspective
  location <0, 2.4, -5.5>
  look_at  <0.3, 0.9, 3>
  right x*4/3
  up y
  angle 52
}
background { rgb <0.25, 0.5, 0.9> }
light_source { <-5, 9, -6> color rgb 1 }

// the board: a 3-D checker of unit cubes, yellow where floor(x) + floor(y) + floor(z) is even
box { <-4, -0.1, -1>, <4, 0, 9>
  pigment { checker color rgb <0.95, 0.85, 0.15> color rgb <0.85, 0.12, 0.1> }
  finish { ambient 0.1 diffuse 0.8 specular 0 phong 0 }
}
// mirror sphere
sphere { <1.4, 1.5, 4.5>, 1.2
  pigment { rgb 0.9 }
  finish { ambient 0 diffuse 0.1 reflection { 0.75 } specular 0.6 roughness 0.005 }
}
// glass sphere (ior 1.5)
sphere { <-0.5, 1.1, 1.2>, 1.0
  pigment { rgbf <1, 1, 1, 0.9> }
  finish { ambient 0 diffuse 0.05 reflection { 0.1 } specular 0.6 roughness 0.005 }
  interior { ior 1.5 }
}
