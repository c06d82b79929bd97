# Plots the accuracy study's CSV files: gnuplot -e "dir='OUTDIR'" scripts/accuracy_plots.gp
set datafile separator ','
set terminal pngcairo size 900,640 enhanced font 'DejaVu Sans,11'
integrators = "explicit_euler semi_implicit_euler position_verlet velocity_verlet rk4 implicit_euler"
problems = "undamped_oscillator damped_oscillator spring_chain drag_projectile damped_projectile rod_pendulum rod_rope"
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
  set ylabel 'largest position error over the run [m]'
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


# Rigid bodies (issue 14), from body_work_precision.csv (columns: problem, metric, substeps,
# iterations, stiffness, contact_hz, joint_hz, value, cpu_s_per_simulated_s, diverged).
bw = dir.'/body_work_precision.csv'
substep_counts = "1 2 4 8"
substep_colour(s) = s == 1 ? '#d62728' : s == 2 ? '#ff7f0e' : s == 4 ? '#2ca02c' : '#1f77b4'
# Log axes cannot show 0 (an exact answer); the absolute value of the signed errors.
magnitude(v) = abs(v) > 0 ? abs(v) : NaN
picked(p, m, s, k) = strcol(1) eq p && strcol(2) eq m && $3 == s && $5 == k && $10 == 0
unset label
set xtics auto
set mxtics
set key outside right top
set bmargin
set xrange [*:*]
set yrange [*:*]
set logscale y
set format y '10^{%L}'
# Room above and below the points, so that none sits on the frame.
set offsets 0, 0, graph 0.05, graph 0.05

# Work-precision: a line per substep count at the default stiffness, iterations 1 to 8 along it.
wp_problems = "hinged_pendulum welded_pendulum cube_stack dropped_stack heavy_light_stack cube_bounce"
wp_metrics = "period_error period_error top_drift top_drift top_drift rebound_error"
wp_labels = "'|T / T_{exact} - 1|' '|T / T_{exact} - 1|' 'top cube moved in 10 s [m]' 'top cube from where it should rest [m]' 'top cube moved in 10 s [m]' '|v_{out} / (e v_{in}) - 1|'"
set logscale x
set format x '10^{%L}'
set xlabel 'CPU time per simulated second [s]'
do for [k = 1:words(wp_problems)] {
  p = word(wp_problems, k)
  m = word(wp_metrics, k)
  set output dir.'/body_work_precision_'.p.'_'.m.'.png'
  set title p.': '.m.' (default stiffness; iterations 1 to 8 along each line)' noenhanced
  set ylabel word(wp_labels, k)
  plot for [s in substep_counts] bw skip 1 using (picked(p, m, s + 0, 1) ? $9 : NaN):(magnitude($8)) \
    with linespoints lw 2 pt 7 lc rgb substep_colour(s + 0) title s.' substeps'
}

# The free tumble: without constraints iterations and stiffness change nothing, so the 8
# iteration counts of each substep count (1, 2, 4, 8 from the left) cluster at one error.
set output dir.'/body_work_precision_torque_free_tumble.png'
set title 'torque_free_tumble: largest drifts in 20 s (substeps 1, 2, 4, 8 from the left)' noenhanced
set ylabel 'relative drift'
tumble(m) = strcol(1) eq 'torque_free_tumble' && strcol(2) eq m && $5 == 1 && $10 == 0
plot bw skip 1 using (tumble('energy_drift') ? $9 : NaN):(magnitude($8)) \
       with linespoints lw 2 pt 7 title '|E / E_0 - 1|', \
     bw skip 1 using (tumble('momentum_drift') ? $9 : NaN):(magnitude($8)) \
       with linespoints lw 2 pt 5 title '| |L| / |L_0| - 1 |', \
     bw skip 1 using (tumble('momentum_turn') ? $9 : NaN):(magnitude($8)) \
       with linespoints lw 2 pt 9 title '|L - L_0| / |L_0|'

# Against iterations: colour for substeps; solid, dashed, dotted for stiffness 1, 0.5, 2 times the
# default (each capped at a quarter of the substep rate, so at 1 and 2 substeps some coincide).
it_problems = "hinged_pendulum welded_pendulum welded_pendulum dropped_stack dropped_stack turned_stack"
it_metrics = "amplitude_change period_error anchor_drift top_drift top_creep top_creep"
it_labels = "'|amplitude after 20 s / 5 deg - 1|' '|T / T_{exact} - 1|' 'largest hinge point drift [m]' 'top cube from where it should rest [m]' 'top cube moved from 2 s to 10 s [m]' 'top cube moved from 2 s to 10 s [m]'"
unset logscale x
set format x '%g'
set xrange [0.5:8.5]
set xtics 1
unset mxtics
set xlabel 'iterations per substep'
do for [k = 1:words(it_problems)] {
  p = word(it_problems, k)
  m = word(it_metrics, k)
  set output dir.'/body_error_vs_iterations_'.p.'_'.m.'.png'
  set title p.': '.m.' against iterations, for each substep count and stiffness' noenhanced
  set ylabel word(it_labels, k)
  plot for [s in substep_counts] bw skip 1 using (picked(p, m, s + 0, 1) ? $4 : NaN):(magnitude($8)) \
         with linespoints lw 2 pt 7 dt 1 lc rgb substep_colour(s + 0) title s.' substeps, 1x', \
       for [s in substep_counts] bw skip 1 using (picked(p, m, s + 0, 0.5) ? $4 : NaN):(magnitude($8)) \
         with linespoints lw 1 pt 6 dt 2 lc rgb substep_colour(s + 0) title s.' substeps, 0.5x', \
       for [s in substep_counts] bw skip 1 using (picked(p, m, s + 0, 2) ? $4 : NaN):(magnitude($8)) \
         with linespoints lw 1 pt 4 dt 3 lc rgb substep_colour(s + 0) title s.' substeps, 2x'
}
