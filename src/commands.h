/* The subcommands of the mimas program, one cmd_*.c file each. */
#ifndef MIMAS_COMMANDS_H
#define MIMAS_COMMANDS_H

#include "cli.h"

extern const cli_command cmd_average;
extern const cli_command cmd_convert;
extern const cli_command cmd_disperse;
extern const cli_command cmd_info;
extern const cli_command cmd_rheology;
extern const cli_command cmd_shearband;
extern const cli_command cmd_simulate;
extern const cli_command cmd_voronoi;
extern const cli_command cmd_energy;
extern const cli_command cmd_xdmf;
extern const cli_command cmd_plugs;
extern const cli_command cmd_radial;
extern const cli_command cmd_plot;

#endif
