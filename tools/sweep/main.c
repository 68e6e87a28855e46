/* tools/sweep/main.c: `cumulo-sweep`, the speed/accuracy sweep against the reference path tracer (sweep.c). */
int cmd_sweep(int argc, char **argv);

int main(int argc, char **argv)
{
    return cmd_sweep(argc, argv);
}
