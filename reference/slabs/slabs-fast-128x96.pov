// POV-Ray 3.7 SDL exported by `photonmap export-pov` from scenes/slabs.scene
// settings: 256x192, quality fast, radiosity on, photons on
// Render single-threaded for reproducibility, linear OpenEXR, no antialiasing:
//   povray +I<this> +O<out>.exr +FE +W256 +H192 -A -J +WT1 -D -V +GS
// (for the renderer's 2x2 subpixels render at 2W x 2H and box-downsample by 2).
// Units: z negated (left-handed); light colour = I/(2 pi D^2) with fade_distance D,
// fade_power 2, so that colour x 2/(1+(d/D)^2) x diffuse 1 = I/(pi d^2).
// Scene bounds diagonal 4.5.
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
// material 'green' (lambert)
#declare PM_Mat2 = material {
  texture { pigment { rgb <0.14, 0.45, 0.091> } finish { diffuse 1 brilliance 1 ambient 0 } }
}

box {
  <-1.00000045, 0, -2.5>, <-1, 2, 1>
  material { PM_Mat1 }  // red
}
box {
  <1, 0, -2.5>, <1.00000045, 2, 1>
  material { PM_Mat2 }  // green
}
box {
  <-1, 0, 1>, <1, 2, 1.00000045>
  material { PM_Mat0 }  // white
}
box {
  <-1, -4.5e-07, -2.5>, <1, 0, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 2, -2.5>, <1, 2.00000045, 1>
  material { PM_Mat0 }  // white
}
box {
  <-1, 0, -2.50000045>, <1, 2, -2.5>
  material { PM_Mat0 }  // white
}
box {
  <-0.99700045, 0.5, -0.49999999999999989>, <-0.997, 0.506, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.60000045, 0.5, -0.49999999999999989>, <-0.6, 0.506, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.50599955, -0.49999999999999989>, <-0.6, 0.506, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.49999955, -0.49999999999999989>, <-0.6, 0.5, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.5, 0.9>, <-0.6, 0.506, 0.90000045000000006>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.5, -0.50000045>, <-0.6, 0.506, -0.5>
  material { PM_Mat0 }  // white
}
box {
  <-0.99700045, 0.9, -0.49999999999999989>, <-0.997, 0.906, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.60000045, 0.9, -0.49999999999999989>, <-0.6, 0.906, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.90599955, -0.49999999999999989>, <-0.6, 0.906, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.89999955, -0.49999999999999989>, <-0.6, 0.9, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.9, 0.9>, <-0.6, 0.906, 0.90000045000000006>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 0.9, -0.50000045>, <-0.6, 0.906, -0.5>
  material { PM_Mat0 }  // white
}
box {
  <-0.99700045, 1.3, -0.49999999999999989>, <-0.997, 1.306, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.60000045, 1.3, -0.49999999999999989>, <-0.6, 1.306, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 1.3059995500000001, -0.49999999999999989>, <-0.6, 1.306, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 1.2999995500000001, -0.49999999999999989>, <-0.6, 1.3, 0.9>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 1.3, 0.9>, <-0.6, 1.306, 0.90000045000000006>
  material { PM_Mat0 }  // white
}
box {
  <-0.997, 1.3, -0.50000045>, <-0.6, 1.306, -0.5>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 0.8, 0.917>, <-0.45, 0.803, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 0.8, 0.917>, <0.45000045, 0.803, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.80299955, 0.917>, <0.45, 0.803, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.79999955, 0.917>, <0.45, 0.8, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.8, 0.997>, <0.45, 0.803, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.8, 0.917>, <0.45, 0.803, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 0.84, 0.917>, <-0.45, 0.843, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 0.84, 0.917>, <0.45000045, 0.843, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.84299954999999993, 0.917>, <0.45, 0.843, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.83999954999999993, 0.917>, <0.45, 0.84, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.84, 0.997>, <0.45, 0.843, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.84, 0.917>, <0.45, 0.843, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 0.88, 0.917>, <-0.45, 0.883, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 0.88, 0.917>, <0.45000045, 0.883, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.88299955, 0.917>, <0.45, 0.883, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.87999955, 0.917>, <0.45, 0.88, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.88, 0.997>, <0.45, 0.883, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.88, 0.917>, <0.45, 0.883, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 0.92, 0.917>, <-0.45, 0.923, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 0.92, 0.917>, <0.45000045, 0.923, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.92299955, 0.917>, <0.45, 0.923, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.91999955, 0.917>, <0.45, 0.92, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.92, 0.997>, <0.45, 0.923, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.92, 0.917>, <0.45, 0.923, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 0.96, 0.917>, <-0.45, 0.963, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 0.96, 0.917>, <0.45000045, 0.963, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.96299954999999993, 0.917>, <0.45, 0.963, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.95999954999999992, 0.917>, <0.45, 0.96, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.96, 0.997>, <0.45, 0.963, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.96, 0.917>, <0.45, 0.963, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1, 0.917>, <-0.45, 1.003, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1, 0.917>, <0.45000045, 1.003, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.00299955, 0.917>, <0.45, 1.003, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 0.99999955, 0.917>, <0.45, 1, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1, 0.997>, <0.45, 1.003, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1, 0.917>, <0.45, 1.003, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.04, 0.917>, <-0.45, 1.043, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.04, 0.917>, <0.45000045, 1.043, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.04299955, 0.917>, <0.45, 1.043, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.03999955, 0.917>, <0.45, 1.04, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.04, 0.997>, <0.45, 1.043, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.04, 0.917>, <0.45, 1.043, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.08, 0.917>, <-0.45, 1.083, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.08, 0.917>, <0.45000045, 1.083, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.08299955, 0.917>, <0.45, 1.083, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.0799995500000001, 0.917>, <0.45, 1.08, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.08, 0.997>, <0.45, 1.083, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.08, 0.917>, <0.45, 1.083, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.12, 0.917>, <-0.45, 1.123, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.12, 0.917>, <0.45000045, 1.123, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.12299955, 0.917>, <0.45, 1.123, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.1199995500000002, 0.917>, <0.45, 1.12, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.12, 0.997>, <0.45, 1.123, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.12, 0.917>, <0.45, 1.123, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.16, 0.917>, <-0.45, 1.1629999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.16, 0.917>, <0.45000045, 1.1629999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.16299955, 0.917>, <0.45, 1.163, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.15999955, 0.917>, <0.45, 1.16, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.16, 0.997>, <0.45, 1.1629999999999998, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.16, 0.917>, <0.45, 1.1629999999999998, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.2, 0.917>, <-0.45, 1.2029999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.2, 0.917>, <0.45000045, 1.2029999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.2029995500000001, 0.917>, <0.45, 1.203, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.19999955, 0.917>, <0.45, 1.2, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.2, 0.997>, <0.45, 1.2029999999999998, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.2, 0.917>, <0.45, 1.2029999999999998, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.24, 0.917>, <-0.45, 1.2429999999999999, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.24, 0.917>, <0.45000045, 1.2429999999999999, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.2429995500000002, 0.917>, <0.45, 1.243, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.23999955, 0.917>, <0.45, 1.24, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.24, 0.997>, <0.45, 1.2429999999999999, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.24, 0.917>, <0.45, 1.2429999999999999, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.28, 0.917>, <-0.45, 1.283, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.28, 0.917>, <0.45000045, 1.283, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.28299955, 0.917>, <0.45, 1.283, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.27999955, 0.917>, <0.45, 1.28, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.28, 0.997>, <0.45, 1.283, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.28, 0.917>, <0.45, 1.283, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.32, 0.917>, <-0.45, 1.323, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.32, 0.917>, <0.45000045, 1.323, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.32299955, 0.917>, <0.45, 1.323, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.3199995500000001, 0.917>, <0.45, 1.32, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.32, 0.997>, <0.45, 1.323, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.32, 0.917>, <0.45, 1.323, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.36, 0.917>, <-0.45, 1.363, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.36, 0.917>, <0.45000045, 1.363, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.36299955, 0.917>, <0.45, 1.363, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.3599995500000002, 0.917>, <0.45, 1.36, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.36, 0.997>, <0.45, 1.363, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.36, 0.917>, <0.45, 1.363, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.4, 0.917>, <-0.45, 1.4029999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.4, 0.917>, <0.45000045, 1.4029999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.40299955, 0.917>, <0.45, 1.403, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.39999955, 0.917>, <0.45, 1.4, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.4, 0.997>, <0.45, 1.4029999999999998, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.4, 0.917>, <0.45, 1.4029999999999998, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.44, 0.917>, <-0.45, 1.4429999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.44, 0.917>, <0.45000045, 1.4429999999999998, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.4429995500000001, 0.917>, <0.45, 1.443, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.43999955, 0.917>, <0.45, 1.44, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.44, 0.997>, <0.45, 1.4429999999999998, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.44, 0.917>, <0.45, 1.4429999999999998, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.48, 0.917>, <-0.45, 1.4829999999999999, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.48, 0.917>, <0.45000045, 1.4829999999999999, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.4829995500000002, 0.917>, <0.45, 1.483, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.47999955, 0.917>, <0.45, 1.48, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.48, 0.997>, <0.45, 1.4829999999999999, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.48, 0.917>, <0.45, 1.4829999999999999, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.52, 0.917>, <-0.45, 1.523, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.52, 0.917>, <0.45000045, 1.523, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.52299955, 0.917>, <0.45, 1.523, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.51999955, 0.917>, <0.45, 1.52, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.52, 0.997>, <0.45, 1.523, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.52, 0.917>, <0.45, 1.523, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <-0.45000045, 1.56, 0.917>, <-0.45, 1.563, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <0.45, 1.56, 0.917>, <0.45000045, 1.563, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.56299955, 0.917>, <0.45, 1.563, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.5599995500000001, 0.917>, <0.45, 1.56, 0.997>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.56, 0.997>, <0.45, 1.563, 0.99700045>
  material { PM_Mat0 }  // white
}
box {
  <-0.45, 1.56, 0.917>, <0.45, 1.563, 0.91700045000000008>
  material { PM_Mat0 }  // white
}
box {
  <0.35, 0, 0>, <0.35000044999999996, 0.7, 0.8>
  material { PM_Mat0 }  // white
}
box {
  <0.356, 0, 0>, <0.35600044999999997, 0.7, 0.8>
  material { PM_Mat0 }  // white
}
box {
  <0.35, 0.69999954999999991, 0>, <0.356, 0.7, 0.8>
  material { PM_Mat0 }  // white
}
box {
  <0.35, 0, 0.8>, <0.356, 0.7, 0.80000045000000009>
  material { PM_Mat0 }  // white
}
box {
  <0.35, 0, -4.5e-07>, <0.356, 0.7, 0>
  material { PM_Mat0 }  // white
}
box {
  <-0.40000045, 0.004, 0.19999999999999996>, <-0.4, 0.01, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <0.1, 0.004, 0.19999999999999996>, <0.10000045, 0.01, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.00999955, 0.19999999999999996>, <0.099999999999999978, 0.01, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.00399955, 0.19999999999999996>, <0.099999999999999978, 0.004, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.004, 0.6>, <0.099999999999999978, 0.01, 0.60000045>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.004, 0.2>, <0.099999999999999978, 0.01, 0.20000045000000002>
  material { PM_Mat0 }  // white
}
box {
  <-0.40000045, 0.014, 0.19999999999999996>, <-0.4, 0.02, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <0.1, 0.014, 0.19999999999999996>, <0.10000045, 0.02, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.01999955, 0.19999999999999996>, <0.099999999999999978, 0.02, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.01399955, 0.19999999999999996>, <0.099999999999999978, 0.014, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.014, 0.6>, <0.099999999999999978, 0.02, 0.60000045>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.014, 0.2>, <0.099999999999999978, 0.02, 0.20000045000000002>
  material { PM_Mat0 }  // white
}
box {
  <-0.40000045, 0.024, 0.19999999999999996>, <-0.4, 0.03, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <0.1, 0.024, 0.19999999999999996>, <0.10000045, 0.03, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.02999955, 0.19999999999999996>, <0.099999999999999978, 0.03, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.02399955, 0.19999999999999996>, <0.099999999999999978, 0.024, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.024, 0.6>, <0.099999999999999978, 0.03, 0.60000045>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.024, 0.2>, <0.099999999999999978, 0.03, 0.20000045000000002>
  material { PM_Mat0 }  // white
}
box {
  <-0.40000045, 0.034, 0.19999999999999996>, <-0.4, 0.04, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <0.1, 0.034, 0.19999999999999996>, <0.10000045, 0.04, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.03999955, 0.19999999999999996>, <0.099999999999999978, 0.04, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.03399955, 0.19999999999999996>, <0.099999999999999978, 0.034, 0.6>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.034, 0.6>, <0.099999999999999978, 0.04, 0.60000045>
  material { PM_Mat0 }  // white
}
box {
  <-0.4, 0.034, 0.2>, <0.099999999999999978, 0.04, 0.20000045000000002>
  material { PM_Mat0 }  // white
}
