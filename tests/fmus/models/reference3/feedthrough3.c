/* A test model after the Modelica Reference FMUs' FMI 3.0 "Feedthrough": an input of every FMI 3.0 type, each
 * with a declared start value (not zero, so that a start value kept is told from a default), and an output that
 * repeats it; a Float64 vector input; two parameters and one state, x' = Float64_fixed_parameter * u - x with u
 * the Float64 continuous input, so that the outputs move in time. Its inputs are meant to be left unconnected:
 * the model starts from the values its modelDescription.xml declares, as FMI requires. */
#include "fmi3_model.h"

typedef struct {
    bool changed;
    float f32c_in, f32c, f32d_in, f32d;
    double p_fixed, p_tunable, f64c_in, f64c, f64d_in, f64d, vec_in[3], vec[3], x;
    int8_t i8_in, i8; uint8_t u8_in, u8; int16_t i16_in, i16; uint16_t u16_in, u16;
    int32_t i32_in, i32; uint32_t u32_in, u32; int64_t i64_in, i64, enum_in, enum_out; uint64_t u64_in, u64;
    bool bool_in, bool_out;
    char *str_in;
    uint8_t bin_in[16]; size_t bin_size;
} Model;

static void outputs(Model *m) {
    m->f32c = m->f32c_in; m->f32d = m->f32d_in; m->f64c = m->f64c_in; m->f64d = m->f64d_in;
    for (int i = 0; i < 3; i++) m->vec[i] = m->vec_in[i];
    m->i8 = m->i8_in; m->u8 = m->u8_in; m->i16 = m->i16_in; m->u16 = m->u16_in; m->i32 = m->i32_in;
    m->u32 = m->u32_in; m->i64 = m->i64_in; m->u64 = m->u64_in; m->bool_out = m->bool_in; m->enum_out = m->enum_in;
}

void *fmi3InstantiateCoSimulation(const char *name, const char *token, const char *resources, bool visible,
                                  bool loggingOn, bool eventModeUsed, bool earlyReturnAllowed,
                                  const VR required[], size_t nRequired, void *env, void *log, void *update) {
    Model *m = calloc(1, sizeof(Model));
    if (!m) return NULL;
    /* the start values of modelDescription.xml */
    m->f32c_in = 0.5f; m->f32d_in = -1.25f; m->p_fixed = 2.0; m->p_tunable = 3.0; m->f64c_in = 1.5; m->f64d_in = 2.5;
    m->vec_in[0] = 1.0; m->vec_in[1] = 2.0; m->vec_in[2] = 3.0;
    m->i8_in = -3; m->u8_in = 200; m->i16_in = -300; m->u16_in = 60000; m->i32_in = -70000; m->u32_in = 4000000000u;
    m->i64_in = -5000000000LL; m->u64_in = 10000000000000000000ULL; m->bool_in = true; m->enum_in = 2;
    m->str_in = strdup("Set me!");
    memcpy(m->bin_in, "foo", 3); m->bin_size = 3;
    outputs(m);
    return m;
}

void fmi3FreeInstance(void *c) { Model *m = (Model *)c; if (m) { free(m->str_in); free(m); } }
Status fmi3SetDebugLogging(void *c, bool on, size_t n, const char *const cats[]) { return OK; }
Status fmi3EnterInitializationMode(void *c, bool tolDefined, double tol, double start, bool stopDefined,
                                   double stop) { return OK; }
Status fmi3ExitInitializationMode(void *c) { outputs((Model *)c); return OK; }
Status fmi3EnterStepMode(void *c) { return OK; }
Status fmi3Terminate(void *c) { return OK; }

Status fmi3DoStep(void *c, double t, double h, bool noSetPrior, bool *eventNeeded, bool *terminate,
                  bool *earlyReturn, double *lastSuccessfulTime) {
    Model *m = (Model *)c;
    m->x += h * (m->p_fixed * m->f64c_in - m->x);
    outputs(m);
    *eventNeeded = false; *terminate = false; *earlyReturn = false; *lastSuccessfulTime = t + h;
    return OK;
}

ACCESS(float, Float32, Model, case 1: p = &m->f32c_in; break; case 2: p = &m->f32c; break;
       case 3: p = &m->f32d_in; break; case 4: p = &m->f32d; break;)
ACCESS(double, Float64, Model, case 5: p = &m->p_fixed; break; case 6: p = &m->p_tunable; break;
       case 7: p = &m->f64c_in; break; case 8: p = &m->f64c; break; case 9: p = &m->f64d_in; break;
       case 10: p = &m->f64d; break; case 35: p = m->vec_in; n = 3; break; case 36: p = m->vec; n = 3; break;
       case 37: p = &m->x; break;)
ACCESS(int8_t, Int8, Model, case 11: p = &m->i8_in; break; case 12: p = &m->i8; break;)
ACCESS(uint8_t, UInt8, Model, case 13: p = &m->u8_in; break; case 14: p = &m->u8; break;)
ACCESS(int16_t, Int16, Model, case 15: p = &m->i16_in; break; case 16: p = &m->i16; break;)
ACCESS(uint16_t, UInt16, Model, case 17: p = &m->u16_in; break; case 18: p = &m->u16; break;)
ACCESS(int32_t, Int32, Model, case 19: p = &m->i32_in; break; case 20: p = &m->i32; break;)
ACCESS(uint32_t, UInt32, Model, case 21: p = &m->u32_in; break; case 22: p = &m->u32; break;)
ACCESS(int64_t, Int64, Model, case 23: p = &m->i64_in; break; case 24: p = &m->i64; break;
       case 33: p = &m->enum_in; break; case 34: p = &m->enum_out; break;)
ACCESS(uint64_t, UInt64, Model, case 25: p = &m->u64_in; break; case 26: p = &m->u64; break;)
ACCESS(bool, Boolean, Model, case 27: p = &m->bool_in; break; case 28: p = &m->bool_out; break;)

Status fmi3GetString(void *c, const VR vr[], size_t nvr, const char *values[], size_t nValues) {
    Model *m = (Model *)c;
    for (size_t i = 0; i < nvr; i++) {
        if (vr[i] != 29 && vr[i] != 30) return ERROR;
        values[i] = m->str_in;   /* the output repeats the input */
    }
    return OK;
}

Status fmi3SetString(void *c, const VR vr[], size_t nvr, const char *const values[], size_t nValues) {
    Model *m = (Model *)c;
    for (size_t i = 0; i < nvr; i++) {
        if (vr[i] != 29) return ERROR;
        char *copy = strdup(values[i] ? values[i] : "");
        if (!copy) return ERROR;
        free(m->str_in);
        m->str_in = copy;
    }
    return OK;
}

Status fmi3GetBinary(void *c, const VR vr[], size_t nvr, size_t sizes[], const uint8_t *values[], size_t nValues) {
    Model *m = (Model *)c;
    for (size_t i = 0; i < nvr; i++) {
        if (vr[i] != 31 && vr[i] != 32) return ERROR;
        sizes[i] = m->bin_size;
        values[i] = m->bin_in;
    }
    return OK;
}

Status fmi3SetBinary(void *c, const VR vr[], size_t nvr, const size_t sizes[], const uint8_t *const values[],
                     size_t nValues) {
    Model *m = (Model *)c;
    for (size_t i = 0; i < nvr; i++) {
        if (vr[i] != 31 || sizes[i] > sizeof m->bin_in) return ERROR;
        memcpy(m->bin_in, values[i], sizes[i]);
        m->bin_size = sizes[i];
    }
    return OK;
}
