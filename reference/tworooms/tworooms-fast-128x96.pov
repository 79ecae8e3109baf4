// POV-Ray 3.7 SDL exported by `photonmap export-pov` from scenes/tworooms.scene
// settings: 256x192, quality fast, radiosity on, photons on
// Render single-threaded for reproducibility, linear OpenEXR, no antialiasing:
//   povray +I<this> +O<out>.exr +FE +W256 +H192 -A -J +WT1 -D -V +GS
// (for the renderer's 2x2 subpixels render at 2W x 2H and box-downsample by 2).
// Units: z negated (left-handed); light colour = I/(2 pi D^2) with fade_distance D,
// fade_power 2, so that colour x 2/(1+(d/D)^2) x diffuse 1 = I/(pi d^2).
// Scene bounds diagonal 5.74978.
// Rectangles are boxes 1e-07 of the diagonal thick (--rect-thickness).

#version 3.7;

global_settings {
  assumed_gamma 1.0
  ambient_light rgb 0
  max_trace_level 32
  adc_bailout 1e-4
  radiosity {
    pretrace_start 0.08
    pretrace_end 0.02
    count 100
    error_bound 0.5
    nearest_count 5
    recursion_limit 20
    low_error_factor 0.5
    gray_threshold 0
    minimum_reuse 0.015
    brightness 1
    adc_bailout 0.001
    always_sample off
    normal off
    media off
  }
  photons {
    count 200000
    gather 20, 100
    autostop 0
    max_trace_level 32
    adc_bailout 1e-4
    media off
  }
}

#default { finish { ambient 0 emission 0 diffuse 1 brilliance 1 specular 0 phong 0 } }

camera {
  perspective
  location <-0.5, 1, -2.3>
  right x*1.3333333333333333
  up y
  sky <0, 1, 0>
  angle 65
  look_at <0.5, 0.8, 0.5>
}

// intensity <1.0000000306883221, 1.0000000306883221, 1.0000000306883221> W/sr
light_source {
  <2.1, 1.75, 0>
  color rgb <159154.94797609351, 159154.94797609351, 159154.94797609351>
  fade_distance 0.001
  fade_power 2
  photons { reflection on refraction on }
}

// material 'white' (lambert)
#declare PM_Mat0 = material {
  texture { pigment { rgb <0.75, 0.75, 0.75> } finish { diffuse 1 brilliance 1 ambient 0 } }
}
// material 'orange' (lambert)
#declare PM_Mat1 = material {
  texture { pigment { rgb <0.75, 0.45, 0.15> } finish { diffuse 1 brilliance 1 ambient 0 } }
}

box {
  <-1.0000005749782606, 0, -2.5>, <-1, 2, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 0, 1>, <1, 2, 1.0000005749782606>
  material { PM_Mat0 }  // white
}
box {
  <-1, -5.7497826045860208e-07, -2.5>, <1, 0, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 2, -2.5>, <1, 2.0000005749782606, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 0, -2.5000005749782606>, <1, 2, -2.5>
  material { PM_Mat0 }  // white
}
box {
  <0.99999942502173955, 0, -2.5>, <1, 2, -1>
  material { PM_Mat0 }  // white
}
box {
  <0.99999942502173955, 0, 0.9>, <1, 2, 1>
  material { PM_Mat0 }  // white
}
box {
  <0.99999942502173955, 0, -1>, <1, 2, -0.1>
  material { PM_Mat0 }  // white
}
box {
  <0.99999942502173955, 1.6, -0.099999999999999978>, <1, 2, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <1, 0, 0.9>, <1.1, 1.6, 0.90000057497826047>
  material { PM_Mat0 }  // white
}
box {
  <1, 0, -0.10000057497826047>, <1.1, 1.6, -0.1>
  material { PM_Mat0 }  // white
}
box {
  <1, 1.5999994250217395, -0.099999999999999978>, <1.1, 1.6, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <1, -5.7497826045860208e-07, -0.099999999999999978>, <1.1, 0, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <1.0999994250217395, 0, 0.9>, <1.1, 2, 1>
  material { PM_Mat0 }  // white
}
box {
  <1.0999994250217395, 0, -1>, <1.1, 2, -0.1>
  material { PM_Mat0 }  // white
}
box {
  <1.0999994250217395, 1.6, -0.099999999999999978>, <1.1, 2, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <3.1, 0, -1>, <3.1000005749782606, 2, 1>
  material { PM_Mat1 }  // orange
}
box {
  <1.1, 0, 1>, <3.1, 2, 1.0000005749782606>
  material { PM_Mat0 }  // white
}
box {
  <1.1, 0, -1.0000005749782606>, <3.1, 2, -1>
  material { PM_Mat0 }  // white
}
box {
  <1.1, -5.7497826045860208e-07, -1>, <3.1, 0, 1>
  material { PM_Mat0 }  // white
}
box {
  <1.1, 2, -1>, <3.1, 2.0000005749782606, 1>
  material { PM_Mat0 }  // white
}
sphere {
  <-0.3, 0.35, 0.3>, 0.35
  material { PM_Mat0 }  // white
}
