/* info.h — `dmbench info`: context, extensions, limits, timer validity. */
#ifndef HARNESS_INFO_H
#define HARNESS_INFO_H

/* Prints the report (JSON when json != 0).  Returns a process exit code. */
int info_main(int json);

#endif
