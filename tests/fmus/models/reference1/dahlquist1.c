/* After the Reference FMUs' Dahlquist (x' = -k x), as an FMI 1.0 co-simulation slave: explicit Euler in
 * sub-steps of at most 0.01 s, the number of steps taken (Integer) and whether x is below 1/2 (Boolean) as
 * outputs that move, and -x as a negated alias of x. A step past the time t_discard (if positive) is computed up
 * to it only and returns fmiDiscard, as FMI 1.0 lets a slave do. */
#define MODEL_IDENTIFIER dahlquist1
#define GUID "{8c4e810f-3df3-4a00-8276-176fa3c9f001}"
#define NR 3
#define NI 1
#define NB 1
#define NS 0

#include "fmi1_slave.h"

enum { vr_x, vr_k, vr_t_discard };

static void start_values(Instance *m) {
    m->r[vr_x] = 1.0;
    m->r[vr_k] = 1.0;
    m->r[vr_t_discard] = -1.0;
    m->i[0] = 0;
    m->b[0] = 0;
}

static void calculate(Instance *m) { m->b[0] = m->r[vr_x] < 0.5; }

static fmiStatus step(Instance *m, double h, double *end) {
    fmiStatus status = fmiOK;
    double t_discard = m->r[vr_t_discard];
    if (t_discard > 0 && *end > t_discard) {
        h = t_discard > m->time ? t_discard - m->time : 0.0;
        *end = m->time + h;
        status = fmiDiscard;
    }
    int n = (int)ceil(h / 0.01 - 1e-9);
    if (n < 1) n = 1;
    double dt = h / n;
    for (int j = 0; j < n; j++) m->r[vr_x] += dt * (-m->r[vr_k] * m->r[vr_x]);
    m->i[0] += 1;
    return status;
}
