/* The round trip of an MPI message between rank 0 and rank 1 (docs/SCALING.md, the cost model's
 * message latency): rank 1 sends a message of N bytes (a request carrying a sweep case's result),
 * rank 0 answers with 8 bytes (the next case index), as the sweep's dispatcher does.
 *   mpirun -n 2 build/bench/mpi_round_trip [N ...]      (default N: 8, 1000, 4000, 100000)
 * Prints the mean round trip in microseconds over 20000 exchanges (2000 for N > 10000). */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2) {
    if (rank == 0) fprintf(stderr, "mpi_round_trip: run it with mpirun -n 2\n");
    MPI_Finalize();
    return 2;
  }
  long sizes[16] = {8, 1000, 4000, 100000};
  int count = 4;
  if (argc > 1) {
    count = 0;
    for (int i = 1; i < argc && count < 16; ++i) sizes[count++] = atol(argv[i]);
  }
  for (int s = 0; s < count; ++s) {
    const long n = sizes[s];
    char* buffer = calloc((size_t)n + 8, 1);
    long long index = 0;
    const int repeats = n > 10000 ? 2000 : 20000;
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = MPI_Wtime();
    for (int r = 0; r < repeats; ++r) {
      if (rank == 1) {
        MPI_Send(buffer, (int)n, MPI_BYTE, 0, 1, MPI_COMM_WORLD);
        MPI_Recv(&index, 1, MPI_LONG_LONG, 0, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      } else if (rank == 0) {
        MPI_Status status;
        MPI_Recv(buffer, (int)n, MPI_BYTE, 1, 1, MPI_COMM_WORLD, &status);
        ++index;
        MPI_Send(&index, 1, MPI_LONG_LONG, 1, 2, MPI_COMM_WORLD);
      }
    }
    const double seconds = MPI_Wtime() - start;
    if (rank == 0) printf("round trip, %ld bytes there and 8 back: %.2f us\n", n, seconds / repeats * 1e6);
    free(buffer);
  }
  MPI_Finalize();
  return 0;
}
