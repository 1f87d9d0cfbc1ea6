/* info.h — `dmbench info`: context, extensions, limits, timer validity. */
#ifndef RUN_INFO_H
#define RUN_INFO_H

/* Prints the report (JSON when json != 0).  Returns a process exit code. */
int info_main(int json);

#endif
