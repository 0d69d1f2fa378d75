set terminal pngcairo size 1000,560 font 'DejaVu Sans,11' noenhanced
set output 'docs/figures/front_profile.png'
set datafile missing '?'
set title 'Front profile after wall_crash at 56 km/h: spread over the middle 80 % of the width idw 81 mm, mls 18 mm (at rest 63 mm)'
set grid
set key center center font ',10'
set xlabel 'across the width: y [m] (vehicle frame, +y left)'
set ylabel 'front-most vertex x in each 0.1 m slice [m]'
set object 1 rect from -0.72, graph 0 to 0.72, graph 1 fillcolor rgb '#eeeeee' fillstyle solid noborder behind
set label 1 'middle 80 % of the width' at 0, graph 0.96 center font ',9'
set offsets 0, 0, graph 0.12, graph 0.12
plot 'docs/figures/front_profile.dat' using 1:2 with linespoints lw 1.5 dt 2 pt 1 lc rgb '#7f7f7f' title 'at rest (before the crash)', \
  '' using 1:3 with linespoints lw 2.5 pt 7 lc rgb '#d62728' title 'idw skin', \
  '' using 1:4 with linespoints lw 2.5 pt 5 lc rgb '#1f77b4' title 'mls skin'
