set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'CPU time per solve (ns)'
set ylabel 'relative error of the velocities against the exact solution'
set yrange [1e-131:100]
set grid
set key top right
set title 'What accuracy costs (bench\_accuracy; black circle: wrong case; exact = 0 drawn at 10^{-130})'
plot 'accuracy-vs-time.dat' index 0 using 2:3 with linespoints pt 7 ps 1.2 title 'paper-4.4-alpha2', \
     '' index 0 using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle, \
     '' index 0 using 2:3:1 with labels offset 0.6,0.6 left font ',8' notitle, \
     '' index 1 using 2:3 with linespoints pt 7 ps 1.2 title 'hard-eps-1e-8', \
     '' index 1 using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle, \
     '' index 1 using 2:3:1 with labels offset 0.6,0.6 left font ',8' notitle, \
     '' index 2 using 2:3 with linespoints pt 7 ps 1.2 title 'hard-mass-ratio-1e12', \
     '' index 2 using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle, \
     '' index 2 using 2:3:1 with labels offset 0.6,0.6 left font ',8' notitle, \
     '' index 3 using 2:3 with linespoints pt 7 ps 1.2 title 'chain-32', \
     '' index 3 using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle, \
     '' index 3 using 2:3:1 with labels offset 0.6,0.6 left font ',8' notitle, \
     '' index 4 using 2:3 with points pt 4 ps 1.6 lw 2 lc rgb 'gray40' title 'general path (n <= 8)', \
     '' index 4 using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle
