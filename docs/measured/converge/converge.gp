set terminal pngcairo size 1100,700 font 'DejaVu Sans,11' noenhanced
set output 'docs/measured/converge/converge.png'
set title 'Crush against the level of detail (built-in sedan)'
set logscale x
set grid
set key top left box opaque
set xrange [40:3000]
set yrange [0:0.9]
set xlabel 'control points N'
set ylabel 'crush [m]'
set datafile separator ','
plot 'docs/measured/converge/converge_wall_crash.csv' using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'wall_crash: residual crush (6 stations, control surface)', \
  'docs/measured/converge/converge_wall_crash.csv' using 1:5 with linespoints lw 2 pt 5 lc rgb '#1f77b4' title 'wall_crash: the same on the car''s surface (render mesh)', \
  'docs/measured/converge/converge_wall_crash.csv' using 1:3 with linespoints lw 1 dt 2 pt 6 lc rgb '#1f77b4' title 'wall_crash: deepest dent', \
  'docs/measured/converge/converge_pole_side.csv' using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'pole_side: residual crush (6 stations, control surface)', \
  'docs/measured/converge/converge_pole_side.csv' using 1:5 with linespoints lw 2 pt 5 lc rgb '#d62728' title 'pole_side: the same on the car''s surface (render mesh)', \
  'docs/measured/converge/converge_pole_side.csv' using 1:3 with linespoints lw 1 dt 2 pt 6 lc rgb '#d62728' title 'pole_side: deepest dent'
