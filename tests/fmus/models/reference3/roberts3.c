/* A test model after the Modelica Reference FMUs' FMI 3.0 "Roberts": Robertson's chemical kinetics, a stiff
 * system, y1' = -0.04 y1 + 1e4 y2 y3, y2' = 0.04 y1 - 1e4 y2 y3 - 3e7 y2^2, with y3 = 1 - y1 - y2 (the
 * algebraic equation of the DAE). No inputs; its outputs y1 and y2 have initial = "exact" start values, and
 * its DefaultExperiment starts at 1e-5 s. Forward Euler with internal steps of at most STEP seconds (stable
 * there: the fast eigenvalue stays below 1e4 1/s over the first seconds). Its archive carries the layered
 * standard's manifest twice, with identical bytes, as the Reference FMUs' build writes it. */
#include "fmi3_model.h"

#define STEP 1e-4

typedef struct {
    bool changed;
    double y1, y2, y3, dy1, dy2;
} Model;

static void update(Model *m) {
    m->y3 = 1.0 - m->y1 - m->y2;
    m->dy1 = -0.04 * m->y1 + 1e4 * m->y2 * m->y3;
    m->dy2 = 0.04 * m->y1 - 1e4 * m->y2 * m->y3 - 3e7 * m->y2 * m->y2;
}

void *fmi3InstantiateCoSimulation(const char *name, const char *token, const char *resources, bool visible,
                                  bool loggingOn, bool eventModeUsed, bool earlyReturnAllowed,
                                  const VR required[], size_t nRequired, void *env, void *log, void *update_) {
    Model *m = calloc(1, sizeof(Model));
    if (!m) return NULL;
    m->y1 = 1.0;   /* the start values of modelDescription.xml */
    m->y2 = 0.0;
    update(m);
    return m;
}

void fmi3FreeInstance(void *c) { free(c); }
Status fmi3SetDebugLogging(void *c, bool on, size_t n, const char *const cats[]) { return OK; }
Status fmi3EnterInitializationMode(void *c, bool tolDefined, double tol, double start, bool stopDefined,
                                   double stop) { return OK; }
Status fmi3ExitInitializationMode(void *c) { update((Model *)c); return OK; }
Status fmi3EnterStepMode(void *c) { return OK; }
Status fmi3Terminate(void *c) { return OK; }

Status fmi3DoStep(void *c, double t, double h, bool noSetPrior, bool *eventNeeded, bool *terminate,
                  bool *earlyReturn, double *lastSuccessfulTime) {
    Model *m = (Model *)c;
    double done = 0.0;
    while (done < h) {
        double dt = h - done < STEP ? h - done : STEP;
        update(m);
        m->y1 += dt * m->dy1;
        m->y2 += dt * m->dy2;
        done += dt;
    }
    update(m);
    *eventNeeded = false; *terminate = false; *earlyReturn = false; *lastSuccessfulTime = t + h;
    return OK;
}

Status fmi3GetFMUState(void *c, void **state) {
    Model *copy = malloc(sizeof(Model));
    if (!copy) return ERROR;
    memcpy(copy, c, sizeof(Model));
    *state = copy;
    return OK;
}
Status fmi3SetFMUState(void *c, void *state) { memcpy(c, state, sizeof(Model)); return OK; }
Status fmi3FreeFMUState(void *c, void **state) { free(*state); *state = NULL; return OK; }

ACCESS(double, Float64, Model, case 2: p = &m->y1; break; case 3: p = &m->dy1; break; case 4: p = &m->y2; break;
       case 5: p = &m->dy2; break; case 6: p = &m->y3; break;)
