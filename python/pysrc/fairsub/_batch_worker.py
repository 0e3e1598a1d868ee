"""A worker process of ``fairsub.batch.run`` without a client: the command line's coordinator
feeds it tasks on standard input and reads one outcome per task on standard output."""

from fairsub import _fairsub

if __name__ == "__main__":
    _fairsub.batch_serve()
