/* Fuzz target: a scenario file of mimas simulate.  The bytes are parsed as
 * INI text (libinih and the key table), checked, printed back; a small box
 * or pull-off scenario is also set up and run for a few steps, so that the
 * set-up and the blow-up detection see what the parser let through. */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "fuzz_input.h"
#include "scenario.h"
#include "setup.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    sim_scenario sc;
    mimas_error err;
    int rc = sim_scenario_load_string(&sc, text, "fuzz.ini", &err);
    free(text);
    if (rc)
        return 0;
    FILE *out = fopen("/dev/null", "w");
    if (out) {
        sim_scenario_print(&sc, out);
        fclose(out);
    }
    /* a few steps of small systems only (the fuzzer must stay fast) */
    int small = (sc.type == SIM_BOX && sc.box_count <= 64) || sc.type == SIM_PULLOFF;
    if (!small)
        return 0;
    dem_system s;
    dem_init(&s);
    sim_plan plan;
    if (sim_setup(&s, &sc, &plan, &err) == MIMAS_OK && dem_neighbours_build(&s, &err) == MIMAS_OK) {
        dem_forces(&s);
        for (int k = 0; k < 20 && k < plan.total_steps; k++) {
            sim_plan_apply(&plan, &s);
            if (dem_step(&s, &err))
                break;
        }
    }
    dem_free(&s);
    return 0;
}
