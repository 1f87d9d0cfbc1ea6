/* gen.h — documents generated from the command table: the man page
 * dmbench.1 and the bash and zsh completion scripts.  Pure functions of
 * the table they are given (hidden commands are left out): the build runs
 * `dmbench __gen-man` and `dmbench __gen-completion bash|zsh`, so what is
 * installed always lists exactly the options the parser accepts. */
#ifndef CLI_GEN_H
#define CLI_GEN_H

#include <stddef.h>
#include <stdio.h>
#include "cli/cli.h"

/* The man page of the commands table[0..n_table), to f. */
void cli_gen_man(const cli_command *table, size_t n_table, FILE *f);
/* The completion script of the commands table[0..n_table) for shell ("bash" or
 * "zsh"), to f; DM_ERR_ARG (nothing written) for another shell. */
int cli_gen_completion(const char *shell, const cli_command *table, size_t n_table, FILE *f);

#endif
