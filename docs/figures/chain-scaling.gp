set logscale xy
set format x '10^{%L}'
set xlabel 'bodies n'
set ylabel 'CPU time per solve (ms)'
set grid
set key top left
set title 'Long chains: time per solve, log-log slope 1.01 for n >= 1000 (bench\_chain)'
plot 'chain-scaling.dat' using 1:2 with linespoints pt 7 ps 1.2 title 'ChainSolver, double', \
     10**(-4.47826) * x**1.01249 with lines dt 2 title 'fit: slope 1.01'
