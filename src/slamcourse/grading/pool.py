"""Sandboxed workers for an engine: started early, handed out fresh, spawned from one thread.

Each submission gets a fresh interpreter (a worker is never reused); the pool only starts the
next one early, so its numpy import is done by the time the learner checks. Every worker is
spawned from one long-lived thread of the pool: bubblewrap's ``--die-with-parent`` follows the
*thread* that started the process, so a worker spawned from a short-lived request thread of a
server would be killed when that thread ends.
"""

from __future__ import annotations

import atexit
import contextlib
import threading
from concurrent.futures import Future, ThreadPoolExecutor

from slamcourse.errors import SandboxError
from slamcourse.sandbox import Limits, Worker, Zygote

ZYGOTE_PRELOAD = ("scipy.linalg", "scipy.sparse.linalg")  # (the latter imports scipy.sparse)
"""What a zygote imports after its first fork: scipy, which optimisers on real data use (0.17 s
per import otherwise, in every worker of an exercise that imports it)."""

_AHEAD_LOCK = threading.Lock()
_AHEAD: dict[bool, Future[Zygote]] = {}  # by require_isolation: a zygote nobody has used yet
_KEPT: dict[bool, Zygote] = {}  # by require_isolation: a zygote reset after one learner
_AHEAD_SPAWNER: ThreadPoolExecutor | None = None  # lives as long as the process (see below)
_LAST_KEPT: dict[bool, bool] = {}  # by require_isolation: whether the last learner's zygote was
# kept for the next (reset clean), in this process


def _lifelong_spawner() -> ThreadPoolExecutor:
    """The thread that spawns every zygote that may outlive the pool that asked for it (one
    started ahead, one kept between learners): bubblewrap's ``--die-with-parent`` follows the
    thread that started it, so it lives as long as the process. Call with ``_AHEAD_LOCK``."""
    global _AHEAD_SPAWNER
    if _AHEAD_SPAWNER is None:
        _AHEAD_SPAWNER = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-ahead")
        atexit.register(_close_ahead)
    return _AHEAD_SPAWNER


def start_zygote_ahead(*, require_isolation: bool) -> None:
    """Start the zygote of the NEXT learner now, while this one is graded (a batch grader's
    process, between submissions): the next forking pool takes it instead of waiting for an
    interpreter, numpy and a sandbox to start (~0.2 s of every submission otherwise). It is a
    fresh zygote that has served nobody, so no two learners share one. It is spawned from a
    thread that lives as long as the process, since bubblewrap's ``--die-with-parent`` follows
    the thread that started it."""
    with _AHEAD_LOCK:
        if require_isolation in _AHEAD:
            return
        _AHEAD[require_isolation] = _lifelong_spawner().submit(
            Zygote.spawn,
            require_isolation=require_isolation,
            preload=ZYGOTE_PRELOAD,
            preload_first=True,  # its scipy import, too, is done before its learner needs it
        )


def zygote_needed_ahead(*, require_isolation: bool) -> bool:
    """Whether the next learner of this process will need a zygote started ahead: not while
    zygotes are kept from one learner to the next (the first learner starts its own, its text
    answers are graded meanwhile, and it is kept), only once a learner's could not be reset or
    none can be kept (without namespaces). A zygote started ahead for nothing costs ~0.4 CPU-s
    (a sandbox, an interpreter, numpy and scipy), which other grading processes could use."""
    with _AHEAD_LOCK:
        return not _LAST_KEPT.get(require_isolation, True)


def _close_ahead() -> None:
    """At exit: close a zygote started ahead that no submission took (the last submissions of
    a batch had no code, or every learner's zygote could be kept for the next), and the one
    kept after the last learner, rather than leave their sockets and sandboxes to the
    interpreter's end."""
    with _AHEAD_LOCK:
        pending = list(_AHEAD.values())
        _AHEAD.clear()
        kept = list(_KEPT.values())
        _KEPT.clear()
    for zygote in kept:
        with contextlib.suppress(Exception):
            zygote.close()
    for future in pending:
        with contextlib.suppress(Exception):
            future.result(timeout=10.0).close()


def _keep(zygote: Zygote, require_isolation: bool) -> None:
    """After a learner's pool closes: keep its zygote for the next learner if it can be reset
    (:meth:`~slamcourse.sandbox.Zygote.reset`: nothing of this learner left in its sandbox),
    else close it."""
    kept = zygote.alive and zygote.reset() is None
    with _AHEAD_LOCK:
        _LAST_KEPT[require_isolation] = kept
        if kept and require_isolation not in _KEPT:  # (a reusing pool's zygote came from the
            _KEPT[require_isolation] = zygote  # lifelong spawner: closed at exit)
            return
    zygote.close()


def _kept(require_isolation: bool) -> Future[Zygote] | None:
    with _AHEAD_LOCK:
        zygote = _KEPT.pop(require_isolation, None)
    if zygote is None:
        return None
    done: Future[Zygote] = Future()
    done.set_result(zygote)
    return done


def _zygote_ahead(require_isolation: bool) -> Future[Zygote] | None:
    with _AHEAD_LOCK:
        return _AHEAD.pop(require_isolation, None)


def _usable(pending: Future[Zygote] | None) -> Future[Zygote] | None:
    """``pending`` unless it is known to have failed or died meanwhile (then it is closed)."""
    if pending is None or not pending.done():
        return pending
    try:
        zygote = pending.result()
    except SandboxError:
        return None
    if zygote.alive:
        return pending
    zygote.close()
    return None


class WorkerPool:
    """Hands out fresh sandboxed workers.

    ``keep_spare``: after each :meth:`take`, start the next worker at once (long-running faces:
    the browser, ``watch``, ``next``). A one-shot command starts one worker early with
    :meth:`warm` and keeps no spare, so no interpreter is started for nothing.

    ``fork``: workers are forked from one sandboxed :class:`~slamcourse.sandbox.Zygote`
    (started by :meth:`warm` or the first :meth:`take`), each a fresh process with its own
    limits, pipes and cgroup, without an interpreter start or numpy import of its own. Workers
    of one zygote share its namespaces (its ``/tmp``, its pid namespace), so a zygote serves
    one learner at a time.

    ``reuse`` (with ``fork``; an engine that serves ONE learner's submission: the batch
    grader): when this pool closes, its zygote is reset (:meth:`~slamcourse.sandbox.Zygote.
    reset`: every worker killed, and the sandbox proven to hold nothing of this learner) and
    kept for the next reusing pool of the process, which then starts no sandbox, interpreter,
    numpy and scipy of its own (~0.3 CPU-s per submission); a zygote that cannot be reset is
    closed, and the next learner gets a fresh one (the one started ahead, if any).
    """

    def __init__(
        self,
        *,
        require_isolation: bool = False,
        limits: Limits | None = None,
        keep_spare: bool = False,
        fork: bool = False,
        reuse: bool = False,
    ) -> None:
        self.require_isolation = require_isolation
        self.limits = limits
        self.keep_spare = keep_spare
        self.fork = fork
        self.reuse = reuse and fork
        self._zygote: Future[Zygote] | None = None
        self._forked: Future[tuple[Zygote, Worker] | None] | None = None
        self._lock = threading.Lock()
        self._spare: Future[Worker] | None = None
        self._spawner: ThreadPoolExecutor | None = None

    def _spawn_later(self) -> Future[Worker]:
        if self._spawner is None:
            self._spawner = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-spawn")
        return self._spawner.submit(
            Worker.spawn, limits=self.limits, require_isolation=self.require_isolation
        )

    def _zygote_later(self) -> Future[Zygote]:
        self._zygote = _usable(self._zygote)  # (e.g. the learner's code killed it: a new one)
        if self._zygote is None and self.reuse:
            self._zygote = _usable(_kept(self.require_isolation))  # reset after a learner
        if self._zygote is None:
            self._zygote = _usable(_zygote_ahead(self.require_isolation))  # started ahead
        if self._spawner is None:
            self._spawner = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-spawn")
        if self._zygote is None:
            if self.reuse:  # it may outlive this pool (and this pool's spawning thread)
                with _AHEAD_LOCK:
                    spawner = _lifelong_spawner()
            else:
                spawner = self._spawner
            self._zygote = spawner.submit(
                Zygote.spawn, require_isolation=self.require_isolation, preload=ZYGOTE_PRELOAD
            )
        return self._zygote

    def warm(self) -> None:
        """Start a worker now, so the next :meth:`take` finds it ready (or nearly)."""
        if self.fork:
            with self._lock:
                self._zygote_later()
            return
        with self._lock:
            if self._spare is None:
                self._spare = self._spawn_later()

    def take(self, limits: Limits | None = None) -> Worker:
        """A fresh worker (the spare when it is alive); raises SandboxError when none can run.
        ``limits`` other than the pool's: a worker started for them (a spare has the pool's)."""
        if self.fork:
            return self._take_forked(limits)
        if limits is not None and limits != self.limits:
            with self._lock:
                if self._spawner is None:
                    self._spawner = ThreadPoolExecutor(
                        max_workers=1, thread_name_prefix="sandbox-spawn"
                    )
                own = self._spawner.submit(
                    Worker.spawn, limits=limits, require_isolation=self.require_isolation
                )
            return own.result()
        with self._lock:
            pending, self._spare = self._spare, None
            if pending is None:
                pending = self._spawn_later()
            if self.keep_spare:
                self._spare = self._spawn_later()
        worker = pending.result()
        if not worker.alive:  # the spare died while waiting (e.g. killed): start another
            worker.close()
            with self._lock:
                again = self._spawn_later()
            worker = again.result()
        return worker

    def _take_forked(self, limits: Limits | None) -> Worker:
        """A worker forked by this pool's zygote; the next one is forked at once, in the
        background, with the same limits, so that joining its cgroups (which can wait for a
        kernel grace period of several milliseconds) and its first frame overlap the exercise
        graded meanwhile. It serves the next exercise whose limits differ only in what the
        grader keeps (time budgets: :meth:`~slamcourse.sandbox.Worker.adopt_limits`), as
        most exercises' do; otherwise it is closed and a worker forked for that exercise."""
        with self._lock:
            pending = self._zygote_later()
            spare, self._forked = self._forked, None
        zygote = pending.result()
        worker = None
        if spare is not None:
            found = spare.result()
            if found is not None:
                owner, candidate = found
                if owner is zygote and candidate.adopt_limits(limits or Limits()):
                    worker = candidate  # (the same process, whatever the time budgets)
                else:
                    candidate.close()
        if worker is None:
            worker = zygote.worker(limits)
        with self._lock:
            if self._spawner is not None and self._zygote is pending:
                self._forked = self._spawner.submit(self._fork_ahead, zygote, limits)
        return worker

    @staticmethod
    def _fork_ahead(zygote: Zygote, limits: Limits | None) -> tuple[Zygote, Worker] | None:
        try:
            worker = zygote.worker(limits)
            worker.wait_ready()
        except SandboxError:
            return None  # the next take forks its own
        return zygote, worker

    def close(self) -> None:
        with self._lock:
            forked, self._forked = self._forked, None
        if forked is not None:
            found = forked.result()
            if found is not None:
                found[1].close()
        with self._lock:
            zygote, self._zygote = self._zygote, None
        if zygote is not None:
            with contextlib.suppress(SandboxError):
                if self.reuse:
                    _keep(zygote.result(), self.require_isolation)
                else:
                    zygote.result().close()
        with self._lock:
            pending, self._spare = self._spare, None
            spawner, self._spawner = self._spawner, None
        if pending is not None:
            with contextlib.suppress(SandboxError):  # it never started: nothing to close
                pending.result().close()
        if spawner is not None:
            spawner.shutdown(wait=True)
