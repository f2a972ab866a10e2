/* Runs a command and writes its peak resident memory (KiB, from wait4's rusage) to
 * $PEAK_RSS_DIR/rank_<OMPI_COMM_WORLD_RANK>.txt: per-rank peak memory of a program that does not
 * report it itself (LAMMPS), started as `mpirun ... peak_rss lmp ...`. Exits with the command's
 * status. */
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: peak_rss COMMAND [ARGS...]\n");
    return 2;
  }
  const pid_t child = fork();
  if (child < 0) return 2;
  if (child == 0) {
    execvp(argv[1], argv + 1);
    perror("peak_rss: exec");
    _exit(127);
  }
  int status = 0;
  struct rusage usage;
  if (wait4(child, &status, 0, &usage) < 0) return 2;
  const char* dir = getenv("PEAK_RSS_DIR");
  const char* rank = getenv("OMPI_COMM_WORLD_RANK");
  if (dir != NULL) {
    char path[4096];
    snprintf(path, sizeof path, "%s/rank_%s.txt", dir, rank != NULL ? rank : "0");
    FILE* out = fopen(path, "w");
    if (out != NULL) {
      fprintf(out, "%ld\n", usage.ru_maxrss);
      fclose(out);
    }
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}
