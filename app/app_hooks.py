"""Server hooks: load the compiled kernel and start the worker processes when the
server starts, so the first page is as quick as the next."""
from .jobs import warm_up


def on_server_loaded(server_context):
    warm_up()
