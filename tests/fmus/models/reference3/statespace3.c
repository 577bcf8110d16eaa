/* A test model after the Modelica Reference FMUs' FMI 3.0 "StateSpace": x' = A x + B u, y = C x + D u, with the
 * numbers of inputs m, states n and outputs r as structural parameters (fixed at 3 here) that give the arrays
 * their dimensions, matrices as array parameters, and the input vector u with a declared start value, meant to
 * be left unconnected. Forward Euler with internal steps of at most STEP seconds inside each DoStep. */
#include "fmi3_model.h"

#define N 3
#define STEP 0.01

typedef struct {
    bool changed;
    uint64_t m, n, r;
    double A[N * N], B[N * N], C[N * N], D[N * N], x0[N], u[N], y[N], x[N];
} Model;

static void outputs(Model *s) {
    for (int i = 0; i < N; i++) {
        s->y[i] = 0.0;
        for (int j = 0; j < N; j++) s->y[i] += s->C[i * N + j] * s->x[j] + s->D[i * N + j] * s->u[j];
    }
}

static void derivatives(const Model *s, const double *x, double *dx) {
    for (int i = 0; i < N; i++) {
        dx[i] = 0.0;
        for (int j = 0; j < N; j++) dx[i] += s->A[i * N + j] * x[j] + s->B[i * N + j] * s->u[j];
    }
}

void *fmi3InstantiateCoSimulation(const char *name, const char *token, const char *resources, bool visible,
                                  bool loggingOn, bool eventModeUsed, bool earlyReturnAllowed,
                                  const VR required[], size_t nRequired, void *env, void *log, void *update) {
    static const double A[N * N] = {-1, 0.5, 0, 0, -2, 1, 0, 0, -4};
    static const double B[N * N] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const double C[N * N] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const double D[N * N] = {0, 0, 0, 0, 0, 0, 0, 0, 0.5};
    static const double x0[N] = {0, 0.25, 0}, u[N] = {1, 2, 3};
    Model *s = calloc(1, sizeof(Model));
    if (!s) return NULL;
    s->m = s->n = s->r = N;   /* the start values of modelDescription.xml */
    memcpy(s->A, A, sizeof A); memcpy(s->B, B, sizeof B); memcpy(s->C, C, sizeof C); memcpy(s->D, D, sizeof D);
    memcpy(s->x0, x0, sizeof x0); memcpy(s->u, u, sizeof u);
    return s;
}

void fmi3FreeInstance(void *c) { free(c); }
Status fmi3SetDebugLogging(void *c, bool on, size_t n, const char *const cats[]) { return OK; }
Status fmi3EnterInitializationMode(void *c, bool tolDefined, double tol, double start, bool stopDefined,
                                   double stop) { return OK; }
Status fmi3ExitInitializationMode(void *c) {
    Model *s = (Model *)c;
    if (s->m != N || s->n != N || s->r != N) return ERROR;   /* this model's structure is fixed */
    memcpy(s->x, s->x0, sizeof s->x);
    outputs(s);
    return OK;
}
Status fmi3EnterStepMode(void *c) { return OK; }
Status fmi3Terminate(void *c) { return OK; }

Status fmi3DoStep(void *c, double t, double h, bool noSetPrior, bool *eventNeeded, bool *terminate,
                  bool *earlyReturn, double *lastSuccessfulTime) {
    Model *s = (Model *)c;
    double done = 0.0, dx[N];
    while (done < h) {
        double dt = h - done < STEP ? h - done : STEP;
        derivatives(s, s->x, dx);
        for (int i = 0; i < N; i++) s->x[i] += dt * dx[i];
        done += dt;
    }
    outputs(s);
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

ACCESS(uint64_t, UInt64, Model, case 1: p = &m->m; break; case 2: p = &m->n; break; case 3: p = &m->r; break;)
ACCESS(double, Float64, Model, case 4: p = m->A; n = N * N; break; case 5: p = m->B; n = N * N; break;
       case 6: p = m->C; n = N * N; break; case 7: p = m->D; n = N * N; break; case 8: p = m->x0; n = N; break;
       case 9: p = m->u; n = N; break; case 10: p = m->y; n = N; break; case 11: p = m->x; n = N; break;)
