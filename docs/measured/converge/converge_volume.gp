set terminal pngcairo size 1100,700 font 'DejaVu Sans,11' noenhanced
set output 'docs/measured/converge/converge_volume.png'
set title 'Crushed volume against the level of detail (built-in sedan)'
set logscale x
set grid
set key bottom right box opaque
set xrange [40:3000]
set yrange [0:*]
set xlabel 'control points N'
set ylabel 'crushed volume [L]'
set datafile separator ','
plot 'docs/measured/converge/converge_wall_crash.csv' using 1:4 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'wall_crash', \
  'docs/measured/converge/converge_pole_side.csv' using 1:4 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'pole_side'
