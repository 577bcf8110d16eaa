/* An FMI 1.0 co-simulation slave around a small model, for the importer's tests (tests/fmus/conftest.py builds
 * each model of this folder into an FMU with the system's C compiler). A model file defines MODEL_IDENTIFIER,
 * GUID, the number of variables of each type (NR, NI, NB, NS: value references 0..N-1 index them) and three
 * functions, then includes this file:
 *   start_values(Instance *) the declared start values,
 *   calculate(Instance *)    the outputs from the state, inputs and parameters,
 *   step(Instance *, h, end) the state advanced over one communication step, ending at *end (a step computed
 *                            in part lowers *end and returns fmiDiscard).
 * Every function of the FMI 1.0 co-simulation API is exported (fmpy binds them all), with the model identifier
 * as prefix, as FMI 1.0 names them. The types are declared here, as FMI 1.0's headers declare them. */

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

typedef void *fmiComponent;
typedef unsigned int fmiValueReference;
typedef double fmiReal;
typedef int fmiInteger;
typedef char fmiBoolean;
typedef const char *fmiString;
typedef enum { fmiOK, fmiWarning, fmiDiscard, fmiError, fmiFatal, fmiPending } fmiStatus;
typedef enum { fmiDoStepStatus, fmiPendingStatus, fmiLastSuccessfulTime } fmiStatusKind;
typedef struct {
    void (*logger)(fmiComponent, fmiString, fmiStatus, fmiString, fmiString, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmiComponent, fmiStatus);
} fmiCallbackFunctions;

#define CAT2(a, b) a##_##b
#define CAT(a, b) CAT2(a, b)
#define FMI(name) CAT(MODEL_IDENTIFIER, name)

typedef struct {
    double r[NR + 1];
    int i[NI + 1];
    fmiBoolean b[NB + 1];
    char *s[NS + 1];
    double time;
    fmiCallbackFunctions cb;
    char name[64];
} Instance;

static void start_values(Instance *m);
static void calculate(Instance *m);
static fmiStatus step(Instance *m, double h, double *end);

static void set_string(Instance *m, unsigned int vr, const char *value) {
    free(m->s[vr]);
    m->s[vr] = strdup(value ? value : "");
}

static fmiStatus fail(Instance *m, const char *message) {
    if (m && m->cb.logger) m->cb.logger(m, m->name, fmiError, "error", "%s", message);
    return fmiError;
}

const char *FMI(fmiGetTypesPlatform)(void) { return "standard32"; }
const char *FMI(fmiGetVersion)(void) { return "1.0"; }
fmiStatus FMI(fmiSetDebugLogging)(fmiComponent c, fmiBoolean on) { (void)c; (void)on; return fmiOK; }

fmiComponent FMI(fmiInstantiateSlave)(fmiString name, fmiString guid, fmiString location, fmiString mime,
                                      fmiReal timeout, fmiBoolean visible, fmiBoolean interactive,
                                      fmiCallbackFunctions functions, fmiBoolean loggingOn) {
    (void)location; (void)mime; (void)timeout; (void)visible; (void)interactive; (void)loggingOn;
    if (!guid || strcmp(guid, GUID) != 0) return NULL;
    Instance *m = calloc(1, sizeof(Instance));
    if (!m) return NULL;
    m->cb = functions;
    strncpy(m->name, name ? name : "", sizeof(m->name) - 1);
    start_values(m);
    return m;
}

fmiStatus FMI(fmiInitializeSlave)(fmiComponent c, fmiReal tStart, fmiBoolean stopTimeDefined, fmiReal tStop) {
    (void)stopTimeDefined; (void)tStop;
    Instance *m = c;
    m->time = tStart;
    calculate(m);
    return fmiOK;
}

fmiStatus FMI(fmiDoStep)(fmiComponent c, fmiReal t, fmiReal h, fmiBoolean newStep) {
    (void)newStep;
    Instance *m = c;
    if (fabs(t - m->time) > 1e-9 * (1.0 + fabs(t))) return fail(m, "fmiDoStep: not at the slave's time");
    if (h < 0) return fail(m, "fmiDoStep: negative step");
    double end = t + h;
    fmiStatus status = step(m, h, &end);
    m->time = end;
    calculate(m);
    return status;
}

fmiStatus FMI(fmiTerminateSlave)(fmiComponent c) { (void)c; return fmiOK; }

fmiStatus FMI(fmiResetSlave)(fmiComponent c) {
    start_values(c);
    return fmiOK;
}

void FMI(fmiFreeSlaveInstance)(fmiComponent c) {
    Instance *m = c;
    if (!m) return;
    for (int k = 0; k < NS; k++) free(m->s[k]);
    free(m);
}

#define ACCESS(T, FIELD, N, COPY)                                                                       \
    Instance *m = c;                                                                                    \
    for (size_t k = 0; k < nvr; k++) {                                                                  \
        if (vr[k] >= (N)) return fail(m, "unknown value reference");                                    \
        COPY;                                                                                           \
    }                                                                                                   \
    return fmiOK;

fmiStatus FMI(fmiGetReal)(fmiComponent c, const fmiValueReference vr[], size_t nvr, fmiReal value[]) {
    ACCESS(fmiReal, r, NR, value[k] = m->r[vr[k]])
}
fmiStatus FMI(fmiGetInteger)(fmiComponent c, const fmiValueReference vr[], size_t nvr, fmiInteger value[]) {
    ACCESS(fmiInteger, i, NI, value[k] = m->i[vr[k]])
}
fmiStatus FMI(fmiGetBoolean)(fmiComponent c, const fmiValueReference vr[], size_t nvr, fmiBoolean value[]) {
    ACCESS(fmiBoolean, b, NB, value[k] = m->b[vr[k]])
}
fmiStatus FMI(fmiGetString)(fmiComponent c, const fmiValueReference vr[], size_t nvr, fmiString value[]) {
    ACCESS(fmiString, s, NS, value[k] = m->s[vr[k]])
}
fmiStatus FMI(fmiSetReal)(fmiComponent c, const fmiValueReference vr[], size_t nvr, const fmiReal value[]) {
    ACCESS(fmiReal, r, NR, m->r[vr[k]] = value[k])
}
fmiStatus FMI(fmiSetInteger)(fmiComponent c, const fmiValueReference vr[], size_t nvr, const fmiInteger value[]) {
    ACCESS(fmiInteger, i, NI, m->i[vr[k]] = value[k])
}
fmiStatus FMI(fmiSetBoolean)(fmiComponent c, const fmiValueReference vr[], size_t nvr, const fmiBoolean value[]) {
    ACCESS(fmiBoolean, b, NB, m->b[vr[k]] = value[k] != 0)
}
fmiStatus FMI(fmiSetString)(fmiComponent c, const fmiValueReference vr[], size_t nvr, const fmiString value[]) {
    ACCESS(fmiString, s, NS, set_string(m, vr[k], value[k]))
}

fmiStatus FMI(fmiSetRealInputDerivatives)(fmiComponent c, const fmiValueReference vr[], size_t nvr,
                                          const fmiInteger order[], const fmiReal value[]) {
    (void)vr; (void)nvr; (void)order; (void)value;
    return fail(c, "fmiSetRealInputDerivatives: canInterpolateInputs is false");
}
fmiStatus FMI(fmiGetRealOutputDerivatives)(fmiComponent c, const fmiValueReference vr[], size_t nvr,
                                           const fmiInteger order[], fmiReal value[]) {
    (void)vr; (void)nvr; (void)order; (void)value;
    return fail(c, "fmiGetRealOutputDerivatives: maxOutputDerivativeOrder is 0");
}
fmiStatus FMI(fmiCancelStep)(fmiComponent c) { return fail(c, "fmiCancelStep: no pending step"); }
fmiStatus FMI(fmiGetStatus)(fmiComponent c, const fmiStatusKind s, fmiStatus *value) {
    (void)s; (void)value;
    return fail(c, "fmiGetStatus: no asynchronous step");
}
fmiStatus FMI(fmiGetRealStatus)(fmiComponent c, const fmiStatusKind s, fmiReal *value) {
    if (s != fmiLastSuccessfulTime) return fail(c, "fmiGetRealStatus: only fmiLastSuccessfulTime");
    *value = ((Instance *)c)->time;
    return fmiOK;
}
fmiStatus FMI(fmiGetIntegerStatus)(fmiComponent c, const fmiStatusKind s, fmiInteger *value) {
    (void)s; (void)value;
    return fail(c, "fmiGetIntegerStatus: no status");
}
fmiStatus FMI(fmiGetBooleanStatus)(fmiComponent c, const fmiStatusKind s, fmiBoolean *value) {
    (void)s; (void)value;
    return fail(c, "fmiGetBooleanStatus: no status");
}
fmiStatus FMI(fmiGetStringStatus)(fmiComponent c, const fmiStatusKind s, fmiString *value) {
    (void)s; (void)value;
    return fail(c, "fmiGetStringStatus: no status");
}
