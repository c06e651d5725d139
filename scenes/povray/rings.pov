// POV-Ray twin (a), written by hand: concentric rings by POV-Ray's built-in wood pattern, the
// colour map sampling eq. 6 (C = Cl + (Cd - Cl) sin(pi u / 2)^6 at 33 points) with 20 mm rings
// (frequency 50 per metre). Its nenrin twin is scenes/povray/rings.json (a straight trunk, no
// variation terms): the same ring field computed by another program.
// Render: povray -D +FE +WT1 +A0.0 +AM2 +R4 -J +W160 +H120 rings.pov
#version 3.7;
global_settings { assumed_gamma 1.0 }

// The nenrin camera: position <0, 0.35, 0.25>, look_at 0, vertical fov 40 at 160 x 120 ->
// horizontal angle 2 atan(tan(20 deg) 4/3). `right -x` keeps nenrin's right-handed frame.
camera { perspective location <0, 0.35, 0.25> look_at <0, 0, 0> sky <0, 1, 0>
         right -x*1.33333333333 up y angle 51.7740087592 }

// The sun: irradiance 3 towards <0.3, 0.9, 0.2>, as colour E / pi for `diffuse 1`.
#declare SunDirection = vnormalize(<0.3, 0.9, 0.2>);
light_source { SunDirection * 1e5 color rgb 0.954929658551 parallel point_at <0, 0, 0> }

// The slab: top face at y = 0 (tree height 2 m, T = 4 + r / 0.02: frac(T) = frac(50 r)).
box { <-0.4, -0.01, -0.4>, <0.4, 0, 0.4>
  texture {
    pigment { wood ramp_wave frequency 50 rotate x*90
      color_map {
    [0.00000 rgb <0.780000, 0.560000, 0.330000>]
    [0.03125 rgb <0.780000, 0.560000, 0.330000>]
    [0.06250 rgb <0.780000, 0.560000, 0.330000>]
    [0.09375 rgb <0.779997, 0.559997, 0.329998>]
    [0.12500 rgb <0.779982, 0.559982, 0.329987>]
    [0.15625 rgb <0.779932, 0.559934, 0.329951>]
    [0.18750 rgb <0.779803, 0.559809, 0.329856>]
    [0.21875 rgb <0.779518, 0.559532, 0.329649>]
    [0.25000 rgb <0.778964, 0.558995, 0.329246>]
    [0.28125 rgb <0.777984, 0.558045, 0.328534>]
    [0.31250 rgb <0.776379, 0.556489, 0.327367>]
    [0.34375 rgb <0.773907, 0.554092, 0.325569>]
    [0.37500 rgb <0.770296, 0.550590, 0.322943>]
    [0.40625 rgb <0.765254, 0.545701, 0.319276>]
    [0.43750 rgb <0.758489, 0.539141, 0.314355>]
    [0.46875 rgb <0.749730, 0.530647, 0.307985>]
    [0.50000 rgb <0.738750, 0.520000, 0.300000>]
    [0.53125 rgb <0.725393, 0.507047, 0.290286>]
    [0.56250 rgb <0.709591, 0.491725, 0.278794>]
    [0.59375 rgb <0.691390, 0.474076, 0.265557>]
    [0.62500 rgb <0.670958, 0.454263, 0.250697>]
    [0.65625 rgb <0.648595, 0.432577, 0.234432>]
    [0.68750 rgb <0.624728, 0.409433, 0.217075>]
    [0.71875 rgb <0.599908, 0.385366, 0.199024>]
    [0.75000 rgb <0.574786, 0.361005, 0.180754>]
    [0.78125 rgb <0.550090, 0.337057, 0.162793>]
    [0.81250 rgb <0.526590, 0.314269, 0.145702>]
    [0.84375 rgb <0.505066, 0.293397, 0.130048>]
    [0.87500 rgb <0.486264, 0.275165, 0.116374>]
    [0.90625 rgb <0.470859, 0.260227, 0.105170>]
    [0.93750 rgb <0.459420, 0.249135, 0.096851>]
    [0.96875 rgb <0.452378, 0.242306, 0.091729>]
    [1.00000 rgb <0.450000, 0.240000, 0.090000>]
      } }
    finish { ambient 0 diffuse 1 } } }
