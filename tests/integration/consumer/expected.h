/* The point the consumers evaluate and the value the table of make_table.cpp holds there:
   fx = 1 + 2 y + 300 spin + 50 y spin, which multilinear interpolation reproduces exactly. */
#ifndef SIM_EXPECTED_H_
#define SIM_EXPECTED_H_
#define SIM_Y 0.5
#define SIM_SPIN 0.005
#define SIM_FX (1.0 + 2.0 * SIM_Y + 300.0 * SIM_SPIN + 50.0 * SIM_Y * SIM_SPIN)
#define SIM_TOLERANCE 1e-12
#endif
