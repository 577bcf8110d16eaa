/* After the Reference FMUs' Feedthrough, as an FMI 1.0 co-simulation slave: an input of each FMI 1.0 type
 * passed to an output (the Real one scaled by a parameter), a String parameter passed through. */
#define MODEL_IDENTIFIER feedthrough1
#define GUID "{8c4e810f-3df3-4a00-8276-176fa3c9f002}"
#define NR 3
#define NI 2
#define NB 2
#define NS 3

#include "fmi1_slave.h"

enum { vr_real_in, vr_real_out, vr_gain };

static void start_values(Instance *m) {
    m->r[vr_real_in] = 0.5;
    m->r[vr_gain] = 2.0;
    m->i[0] = 2;
    m->b[0] = 1;
    set_string(m, 0, "Set me!");
    set_string(m, 2, "label");
}

static void calculate(Instance *m) {
    m->r[vr_real_out] = m->r[vr_gain] * m->r[vr_real_in];
    m->i[1] = m->i[0];
    m->b[1] = m->b[0];
    set_string(m, 1, m->s[0]);
}

static fmiStatus step(Instance *m, double h, double *end) { (void)m; (void)h; (void)end; return fmiOK; }
