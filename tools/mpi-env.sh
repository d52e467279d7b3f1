# Sourced by the scripts: Open MPI refuses to run as root without these (containers, CI), and runs with
# more ranks than cores need --oversubscribe (set in the test launcher and run-example.sh).
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Quieter Open MPI in containers without a high-speed network.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
