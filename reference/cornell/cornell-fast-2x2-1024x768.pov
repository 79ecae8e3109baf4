// POV-Ray 3.7 SDL exported by `photonmap export-pov` from scenes/cornell.scene
// settings: 2048x1536, quality fast, radiosity on, photons on
// Render single-threaded for reproducibility, linear OpenEXR, no antialiasing:
//   povray +I<this> +O<out>.exr +FE +W2048 +H1536 -A -J +WT1 -D -V +GS
// (for the renderer's 2x2 subpixels render at 2W x 2H and box-downsample by 2).
// Units: z negated (left-handed); light colour = I/(2 pi D^2) with fade_distance D,
// fade_power 2, so that colour x 2/(1+(d/D)^2) x diffuse 1 = I/(pi d^2).
// Scene bounds diagonal 4.5.

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
  location <0, 1, -2.4>
  right x*1.3333333333333333
  up y
  sky <0, 1, 0>
  angle 65
  look_at <0, 1, 0>
}

// intensity <1.0000000306883221, 1.0000000306883221, 1.0000000306883221> W/sr
light_source {
  <0, 1.75, 0>
  color rgb <159154.94797609351, 159154.94797609351, 159154.94797609351>
  fade_distance 0.001
  fade_power 2
  photons { reflection on refraction on }
}

// material 'white' (lambert)
#declare PM_Mat0 = material {
  texture { pigment { rgb <0.75, 0.75, 0.75> } finish { diffuse 1 brilliance 1 ambient 0 } }
}
// material 'red' (lambert)
#declare PM_Mat1 = material {
  texture { pigment { rgb <0.63, 0.065, 0.05> } finish { diffuse 1 brilliance 1 ambient 0 } }
}
// material 'mirror' (mirror)
#declare PM_Mat2 = material {
  texture { pigment { rgb 0 } finish { diffuse 0 ambient 0 reflection { rgb <0.9, 0.9, 0.9> } } }
}
// material 'glass' (glass)
#declare PM_Mat3 = material {
  texture { pigment { rgbf <1, 1, 1, 1> }
            finish { diffuse 0 ambient 0 reflection { 0, 1 fresnel on } conserve_energy } }
  interior { ior 1.5 }
}

box {
  <-1.0045, 0, -2.5>, <-1, 2, 1>
  material { PM_Mat1 }  // red
}
box {
  <1, 0, -2.5>, <1.0045, 2, 1>
  material { PM_Mat2 }  // mirror
  photons { target reflection on refraction off collect off }
}
box {
  <-1, 0, 1>, <1, 2, 1.0045>
  material { PM_Mat0 }  // white
}
box {
  <-1, -0.0045000000000000005, -2.5>, <1, 0, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 2, -2.5>, <1, 2.0045, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 0, -2.5045>, <1, 2, -2.5>
  material { PM_Mat0 }  // white
}
sphere {
  <-0.5, 0.35, 0.45>, 0.35
  material { PM_Mat0 }  // white
}
sphere {
  <0.5, 0.35, 0.5>, 0.35
  material { PM_Mat2 }  // mirror
  photons { target reflection on refraction off collect off }
}
sphere {
  <0.05, 0.3, -0.35>, 0.3
  material { PM_Mat3 }  // glass
  photons { target reflection on refraction on collect off }
}
