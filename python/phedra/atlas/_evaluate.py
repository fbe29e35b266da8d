"""One design's row of the atlas, and a chunk of them in a child process that
a time limit or a crash cannot take the sweep down with (docs/atlas.md).

The child (python -m phedra.atlas._child) reads pickled messages on stdin:
("setup", SETUP) and ("rows", VALUES); it answers each row with a pickled
(valid, error, figures). The parent gives each design `time_limit` seconds: past
it, or when the child dies, the design is recorded with the reason and a new
child carries on with the next one."""

import math
import os
import pickle
import select
import signal
import struct
import subprocess
import sys
import threading
import time

from .. import _core
from .._core import Error

_HEADER = struct.Struct("<Q")


def evaluate(setup, row):
    """(valid, error, figures) of the design with parameter values `row`:
    figures a list of floats in setup["figures"]'s order (NaN: undefined; a
    boolean figure 1.0 or 0.0)."""
    names, options = setup["figures"], setup["options"]
    nan = [math.nan] * len(names)
    try:
        preset = _core.with_fields(setup["base"], {path: float(v) for path, v in zip(setup["paths"], row)})
        design = _core.load(preset)
    except Error as e:
        return False, str(e), nan
    try:
        f = design.figures(names, samples=options["samples"], axes=options["axes"], thickness=options["thickness"],
                           max_growth=options["max_growth"], max_panel_ratio=options["max_panel_ratio"])
    except Error as e:
        return True, f"its figures: {e}", nan
    return True, "", [math.nan if f[n] is None else float(f[n]) for n in names]


# -- framing -----------------------------------------------------------------

def _send(stream, message):
    data = pickle.dumps(message, protocol=pickle.HIGHEST_PROTOCOL)
    stream.write(_HEADER.pack(len(data)) + data)
    stream.flush()


def _read_exactly(fd, n, deadline):
    """n bytes from fd; None at end of file; TimeoutError past the deadline."""
    chunks, got = [], 0
    while got < n:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([fd], [], [], left)[0]:
                raise TimeoutError
        data = os.read(fd, n - got)
        if not data:
            return None
        chunks.append(data)
        got += len(data)
    return b"".join(chunks)


def _receive(fd, deadline=None):
    header = _read_exactly(fd, _HEADER.size, deadline)
    if header is None:
        return None
    data = _read_exactly(fd, _HEADER.unpack(header)[0], deadline)
    return None if data is None else pickle.loads(data)


# -- the child ---------------------------------------------------------------

def _watch_parent(parent):
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(0)


def child_main():
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is for the sweep: this process ends with its pipe
    threading.Thread(target=_watch_parent, args=(os.getppid(),), daemon=True).start()
    fd, out = sys.stdin.buffer.fileno(), sys.stdout.buffer
    sys.stdout = sys.stderr  # nothing but messages on the pipe
    setup = None
    while True:
        message = _receive(fd)
        if message is None:
            return
        kind, payload = message
        if kind == "setup":
            setup = payload
        else:
            for row in payload:
                _send(out, evaluate(setup, row))


# -- the parent ----------------------------------------------------------------

def _signal_name(code):
    try:
        return signal.Signals(-code).name
    except ValueError:
        return f"signal {-code}"


class Child:
    """A child process evaluating designs; restarted when it dies or is killed."""

    def __init__(self):
        self.process = None
        self.setup_key = None

    def _start(self, setup, key):
        self.process = subprocess.Popen([sys.executable, "-m", "phedra.atlas._child"], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, env=dict(os.environ, OMP_NUM_THREADS="1"))
        _send(self.process.stdin, ("setup", setup))
        self.setup_key = key

    def _stop(self):
        if self.process is not None:
            self.process.kill()
            self.process.wait()
            self.process.stdin.close()
            self.process.stdout.close()
            self.process = None

    def run(self, setup, key, rows):
        """The rows' results in order; a design past setup's time limit or whose
        evaluation ended the child is recorded invalid with the reason."""
        limit = setup["options"]["time_limit"]
        results, next_row = [], 0
        while next_row < len(rows):
            if self.process is None or self.process.poll() is not None or self.setup_key != key:
                self._stop()
                self._start(setup, key)
            try:
                _send(self.process.stdin, ("rows", [list(r) for r in rows[next_row:]]))
            except BrokenPipeError:
                self._stop()
                continue
            while next_row < len(rows):
                try:
                    result = _receive(self.process.stdout.fileno(), time.monotonic() + limit)
                except TimeoutError:
                    self._stop()
                    result = (False, f"its evaluation took longer than the time limit of {limit:g} s "
                                     "(options.time_limit) and was stopped", None)
                if result is None:  # the child ended during this design
                    code = self.process.wait()
                    self._stop()
                    why = f"killed by {_signal_name(code)}" if code < 0 else f"exit status {code}"
                    result = (False, f"its evaluation ended the process evaluating it ({why})", None)
                if result[2] is None:
                    result = (result[0], result[1], [math.nan] * len(setup["figures"]))
                results.append(result)
                next_row += 1
                if self.process is None:
                    break
        return results


_children = {}
_children_lock = threading.Lock()


def shared_setup(setup):
    """The sweep's setup as a task's result, which the chunks' tasks depend on.
    Not scattered data: Dask's active memory manager keeps one replica of a
    scattered key, and a scattered key lost with its worker cannot be made again
    (every task depending on it is cancelled); a task's result is recomputed."""
    return setup


def evaluate_chunk(setup, key, rows):
    """The results of `rows` (parameter values), in a child process of this
    thread's own (a Dask task runs this)."""
    thread = threading.get_ident()
    with _children_lock:
        child = _children.setdefault(thread, Child())
    return child.run(setup, key, rows)

