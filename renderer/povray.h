/* povray: exporting a scene as POV-Ray 3.7 SDL, radiometrically matched to
 * the renderer (see scenes/README.md and reference/README.md). */
#ifndef PM_POVRAY_H
#define PM_POVRAY_H

/* `photonmap export-pov SCENE [options]`: returns the process exit code. */
int povray_main(int argc, char **argv);

#endif
