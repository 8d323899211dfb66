/* Fuzz target: a contact local dump beside a fixed, valid per-atom dump
 * (ids 1..4 at timesteps 0, 10 and 20).  The first byte picks how the
 * columns are named: LIGGGHTS keywords, LAMMPS names, or the header's own. */
#include <config.h>

#include <string.h>
#include <unistd.h>

#include "fuzz_input.h"

static const char atoms_text[] =
    "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n4\nITEM: BOX BOUNDS xy xz yz pp pp pp\n"
    "0 1 0.1\n0 1 0\n0 1 0\nITEM: ATOMS id type x y z radius\n"
    "1 1 0.1 0.1 0.1 0.1\n2 1 0.25 0.1 0.1 0.1\n3 1 0.9 0.9 0.9 0.1\n4 1 0.5 0.5 0.5 0.2\n"
    "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n4\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id type x y z radius\n"
    "1 1 0.1 0.1 0.1 0.1\n2 1 0.25 0.1 0.1 0.1\n3 1 0.9 0.9 0.9 0.1\n4 1 0.5 0.5 0.5 0.2\n"
    "ITEM: TIMESTEP\n20\nITEM: NUMBER OF ATOMS\n4\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id type x y z radius\n"
    "4 1 0.1 0.1 0.1 0.1\n3 1 0.25 0.1 0.1 0.1\n2 1 0.9 0.9 0.9 0.1\n1 1 0.5 0.5 0.5 0.2\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static const char *columns[3] = {
        "pos,vel,id,force,force_normal,force_tangential,history,delta,contactPoint",
        "patom1,patom2,dist,fx,fy,fz", NULL};
    const char *atoms = fuzz_file((const uint8_t *)atoms_text, sizeof atoms_text - 1, "atoms", 0);
    const char *pairs = fuzz_file(data + 1, size - 1, "pgl", 1);
    if (!atoms || !pairs)
        return 0;
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.contacts = &pairs;
    o.ncontacts = 1;
    o.contact_columns = columns[data[0] % 3];
    o.allow_missing_contacts = (data[0] >> 2) & 1;
    fuzz_read_all(&atoms, 1, &o);
    unlink(atoms);
    unlink(pairs);
    return 0;
}
