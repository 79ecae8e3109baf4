/* povray: placeholder until the exporter lands (issue 4). */
#include "povray.h"

#include <stdio.h>

int povray_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "photonmap: export-pov is not implemented yet\n");
    return 1;
}
