# Plots the accuracy study's CSV files: gnuplot -e "dir='OUTDIR'" scripts/accuracy_plots.gp
set datafile separator ','
set terminal pngcairo size 900,640 enhanced font 'DejaVu Sans,11'
integrators = "explicit_euler semi_implicit_euler position_verlet velocity_verlet rk4 implicit_euler"
problems = "undamped_oscillator damped_oscillator spring_chain drag_projectile damped_projectile"
wp = dir.'/work_precision.csv'
set grid
set key outside right top

set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
do for [p in problems] {
  set output dir.'/work_precision_'.p.'.png'
  set title 'Work-precision: '.p.' (diverged runs left out)' noenhanced
  set xlabel 'CPU time per simulated second [s]'
  set ylabel 'final position error [m]'
  plot for [i in integrators] wp skip 1 \
    using ((strcol(1) eq p && strcol(2) eq i && $6 == 0) ? $5 : NaN):4 with linespoints title i noenhanced
  set output dir.'/error_vs_dt_'.p.'.png'
  set title 'Error against dt: '.p.' (diverged runs left out)' noenhanced
  set xlabel 'dt [s]'
  plot for [i in integrators] wp skip 1 \
    using ((strcol(1) eq p && strcol(2) eq i && $6 == 0) ? $3 : NaN):4 with linespoints title i noenhanced
}

set output dir.'/energy_drift.png'
set title 'Energy drift: undamped oscillator, omega dt = 0.05, 1e5 steps (explicit Euler leaves the plot: 2.7e108 at the end)'
set xlabel 'simulated time [s]'
set ylabel '|E/E_0 - 1|'
set logscale x
set logscale y
set yrange [1e-7:1e3]
plot for [i in integrators] dir.'/energy_drift.csv' skip 1 \
  using (strcol(1) eq i ? $3 : NaN):($4 > 0 ? $4 : 1e-16) with lines lw 2 title i noenhanced
set yrange [*:*]

set output dir.'/stability_map.png'
set title 'Largest stable omega dt (undamped spring, bisection) against theory'
set key inside top left
set bmargin 4
set xlabel ''
set ylabel 'omega dt'
unset logscale x
unset logscale y
set format y '%g'
set yrange [0:3.6]
set xrange [-0.5:5.5]
set xtics ("explicit\nEuler" 0, "semi-implicit\nEuler" 1, "position\nVerlet" 2, \
           "velocity\nVerlet" 3, "RK4" 4, "implicit\nEuler" 5)
set format x '%g'
set label 1 "bounded at 1e3 and 1e6:\nno limit (theory: none)" at 4.45,3.1 font ',9'
set label 2 "theory 0: grows for any omega dt;\nthe measured edge falls\nas the run gets longer" at -0.4,1.0 font ',9'
idx(name) = (name eq 'explicit_euler') ? 0 : (name eq 'semi_implicit_euler') ? 1 : \
            (name eq 'position_verlet') ? 2 : (name eq 'velocity_verlet') ? 3 : \
            (name eq 'rk4') ? 4 : 5
shown(v) = v > 10 ? 3.35 : v
sm = dir.'/stability_map.csv'
plot sm skip 1 using (idx(strcol(1)) - 0.15):($2 == 1000 ? shown($3) : NaN) with points pt 7 ps 1.5 title 'measured, 1e3 steps', \
     sm skip 1 using (idx(strcol(1))):($2 == 10000 ? shown($3) : NaN) with points pt 5 ps 1.5 title 'measured, 1e4 steps', \
     sm skip 1 using (idx(strcol(1)) + 0.15):($2 == 100000 ? shown($3) : NaN) with points pt 9 ps 1.8 title 'measured, 1e5 steps', \
     sm skip 1 using (idx(strcol(1)) - 0.3):(($2 == 100000 && $4 > 0 && $4 < 1e300) ? $4 : NaN):(0.6):(0) with vectors nohead lw 2 lc rgb 'black' title 'theory: 2 (symplectic Euler, Verlet), 2 sqrt 2 (RK4)'
