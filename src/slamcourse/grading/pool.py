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
import re
import threading
from collections import deque
from collections.abc import Sequence
from concurrent.futures import Future, ThreadPoolExecutor

from slamcourse.errors import SandboxError
from slamcourse.sandbox import Limits, Worker, Zygote

ZYGOTE_PRELOAD = ("scipy.linalg", "scipy.sparse.linalg")  # (the latter imports scipy.sparse)
"""What a zygote imports after its first fork: scipy, which optimisers on real data use (0.17 s
per import otherwise, in every worker of an exercise that imports it)."""

Flavour = tuple[bool, bool]
"""A kind of zygote: (``require_isolation``, whether it preloads scipy)."""

_AHEAD_LOCK = threading.Lock()
_AHEAD: dict[Flavour, Future[Zygote]] = {}  # a zygote nobody has used yet
_KEPT: dict[Flavour, Zygote] = {}  # a zygote reset after one learner
_AHEAD_SPAWNER: ThreadPoolExecutor | None = None  # lives as long as the process (see below)
_LAST_KEPT: dict[Flavour, bool] = {}  # whether the last learner's zygote was kept for the next
# (reset clean), in this process


def uses_scipy(source: str) -> bool:
    """Whether a learner's source names scipy (its worker then comes from a zygote that has
    imported it; code that imports it without naming it still works, importing it itself)."""
    return re.search(r"\bscipy\b", source) is not None


def _preload(scipy: bool) -> tuple[str, ...]:
    return ZYGOTE_PRELOAD if scipy else ()


def _lifelong_spawner() -> ThreadPoolExecutor:
    """The thread that spawns every zygote that may outlive the pool that asked for it (one
    started ahead, one kept between learners): bubblewrap's ``--die-with-parent`` follows the
    thread that started it, so it lives as long as the process. Call with ``_AHEAD_LOCK``."""
    global _AHEAD_SPAWNER
    if _AHEAD_SPAWNER is None:
        _AHEAD_SPAWNER = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-ahead")
        atexit.register(_close_ahead)
    return _AHEAD_SPAWNER


def start_zygote_ahead(*, require_isolation: bool, scipy: bool = True) -> None:
    """Start the zygote of the NEXT learner now, while this one is graded (a batch grader's
    process, between submissions): the next forking pool takes it instead of waiting for an
    interpreter, numpy and a sandbox to start (~0.2 s of every submission otherwise). It is a
    fresh zygote that has served nobody, so no two learners share one. It is spawned from a
    thread that lives as long as the process, since bubblewrap's ``--die-with-parent`` follows
    the thread that started it."""
    with _AHEAD_LOCK:
        if (require_isolation, scipy) in _AHEAD:
            return
        _AHEAD[require_isolation, scipy] = _lifelong_spawner().submit(
            Zygote.spawn,
            require_isolation=require_isolation,
            preload=_preload(scipy),
            preload_first=True,  # its scipy import, too, is done before its learner needs it
        )


def zygote_needed_ahead(*, require_isolation: bool, scipy: bool = True) -> bool:
    """Whether the next learner of this process will need a zygote started ahead: not while
    zygotes are kept from one learner to the next (the first learner starts its own, its text
    answers are graded meanwhile, and it is kept), only once a learner's could not be reset or
    none can be kept (without namespaces). A zygote started ahead for nothing costs ~0.4 CPU-s
    (a sandbox, an interpreter, numpy and scipy), which other grading processes could use."""
    with _AHEAD_LOCK:
        return not _LAST_KEPT.get((require_isolation, scipy), True)


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


def _keep(zygote: Zygote, flavour: Flavour) -> None:
    """After a learner's pool closes: keep its zygote for the next learner if it can be reset
    (:meth:`~slamcourse.sandbox.Zygote.reset`: nothing of this learner left in its sandbox),
    else close it."""
    kept = zygote.alive and zygote.reset() is None
    with _AHEAD_LOCK:
        _LAST_KEPT[flavour] = kept
        if kept and flavour not in _KEPT:  # (a reusing pool's zygote came from the
            _KEPT[flavour] = zygote  # lifelong spawner: closed at exit)
            return
    zygote.close()


def _kept(flavour: Flavour) -> Future[Zygote] | None:
    with _AHEAD_LOCK:
        zygote = _KEPT.pop(flavour, None)
    if zygote is None:
        return None
    done: Future[Zygote] = Future()
    done.set_result(zygote)
    return done


def _zygote_ahead(flavour: Flavour) -> Future[Zygote] | None:
    with _AHEAD_LOCK:
        return _AHEAD.pop(flavour, None)


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

    A reusing pool keeps two zygotes, one that has imported scipy and one that has not, and
    forks each worker from the one its source needs (:func:`uses_scipy`): a zygote's
    imports are in every worker it forks, and scipy's (18 MB of objects) made each fork,
    first writes and exit cost 1.1 ms more (5.1 ms instead of 4.0 ms per worker, all CPU
    counted) for the 48 of 55 code exercises whose solutions never use it. Other pools fork
    every worker from one zygote that has imported scipy: they serve one learner's checks
    one at a time, and a second zygote would cost more to start than it saves.
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
        self._zygotes: dict[bool, Future[Zygote] | None] = {}  # by whether it has scipy
        self._forked: Future[tuple[Zygote, Worker] | None] | None = None
        self._lock = threading.Lock()
        self._spare: Future[Worker] | None = None
        self._spawner: ThreadPoolExecutor | None = None
        self._upcoming: deque[tuple[Limits | None, bool]] | None = None  # see expect()

    def _own_spawner(self) -> ThreadPoolExecutor:
        """This pool's spawning thread, started when first needed. Call with ``_lock``."""
        if self._spawner is None:
            self._spawner = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-spawn")
        return self._spawner

    def _spawn_later(self) -> Future[Worker]:
        return self._own_spawner().submit(
            Worker.spawn, limits=self.limits, require_isolation=self.require_isolation
        )

    def _scipy(self, scipy: bool) -> bool:
        """Whether a worker whose source does (not) use scipy comes from the zygote that has
        imported it: always, unless this pool reuses its zygotes (see the class)."""
        return scipy or not self.reuse

    def _zygote_later(self, scipy: bool) -> Future[Zygote]:
        """The zygote with (or without) scipy, started if need be. Call with ``_lock``."""
        flavour = (self.require_isolation, scipy)
        # (e.g. the learner's code killed it: a new one)
        zygote = _usable(self._zygotes.get(scipy))
        if zygote is None and self.reuse:
            zygote = _usable(_kept(flavour))  # reset after a learner
        if zygote is None:
            zygote = _usable(_zygote_ahead(flavour))  # started ahead
        if zygote is None:
            if self.reuse:  # it may outlive this pool (and this pool's spawning thread)
                with _AHEAD_LOCK:
                    spawner = _lifelong_spawner()
            else:
                spawner = self._own_spawner()
            zygote = spawner.submit(
                Zygote.spawn, require_isolation=self.require_isolation, preload=_preload(scipy)
            )
        self._zygotes[scipy] = zygote
        return zygote

    def warm(self) -> None:
        """Start a worker now, so the next :meth:`take` finds it ready (or nearly): the
        zygote, or a reusing pool's two zygotes (the one with scipy only as the second)."""
        if self.fork:
            with self._lock:
                for scipy in dict.fromkeys((self._scipy(False), True)):
                    self._zygote_later(scipy)
            return
        with self._lock:
            if self._spare is None:
                self._spare = self._spawn_later()

    def take(self, limits: Limits | None = None, *, scipy: bool = True) -> Worker:
        """A fresh worker (the spare when it is alive); raises SandboxError when none can run.
        ``limits`` other than the pool's: a worker started for them (a spare has the pool's).
        ``scipy``: whether the code it will run uses scipy (:func:`uses_scipy`; a reusing
        pool forks it from the zygote that has imported scipy, or from the one that has not)."""
        if self.fork:
            return self._take_forked(limits, self._scipy(scipy))
        if limits is not None and limits != self.limits:
            with self._lock:
                own = self._own_spawner().submit(
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

    def expect(self, upcoming: Sequence[tuple[Limits | None, bool]]) -> None:
        """The workers the next takes of this pool will ask for, in order: ``(limits,
        scipy)`` as :meth:`take` gets them (a batch submission's code exercises). Each worker
        forked ahead is then forked with the limits, and from the zygote, that the next take
        needs, and none after the last. Guessing (the same as the last take) wasted 4–5 forked
        workers per complete submission: three exercises whose process limits differ from the
        one before, the switch to the zygote with scipy, and the end; each cost a fork, a
        cgroup join and an exit (~5 ms of CPU), and the take that found no worker ready waited
        for one to be forked (a kernel grace period: ~10 ms). A take that asks for something
        else drops the expected workers before the one it matches (an answer graded without a
        worker). The first one is forked at once (a batch grades a submission's text answers
        meanwhile)."""
        with self._lock:
            self._upcoming = deque((limits, self._scipy(scipy)) for limits, scipy in upcoming)
            if self._upcoming and self.fork and self._forked is None:
                limits, scipy = self._upcoming[0]
                pending = self._zygote_later(scipy)
                self._forked = self._own_spawner().submit(self._fork_ahead, pending, limits)

    def _next_after(self, limits: Limits | None, scipy: bool) -> tuple[Limits | None, bool] | None:
        """What to fork ahead after a take of ``(limits, scipy)``: the next expected worker
        (:meth:`expect`), none after the last, or, with nothing expected, the same again.
        Call with ``_lock``."""
        upcoming = self._upcoming
        if upcoming is None:
            return limits, scipy
        if (limits, scipy) in upcoming:
            while upcoming.popleft() != (limits, scipy):
                pass
        return upcoming[0] if upcoming else None

    def _take_forked(self, limits: Limits | None, scipy: bool) -> Worker:
        """A worker forked by this pool's zygote; the next one is forked at once, in the
        background, so that joining its cgroups (which can wait for a kernel grace period of
        several milliseconds) and its first frame overlap the exercise graded meanwhile: with
        the limits and from the zygote the next take needs (:meth:`expect`), else with the
        same limits from the same zygote. It serves the next exercise whose limits differ
        only in what the grader keeps (time budgets:
        :meth:`~slamcourse.sandbox.Worker.adopt_limits`); otherwise (or when it came from
        the other zygote) it is closed and a worker forked for that exercise."""
        with self._lock:
            pending = self._zygote_later(scipy)
            spare, self._forked = self._forked, None
            following = self._next_after(limits, scipy)
            ahead = None if following is None else self._zygote_later(following[1])
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
        with self._lock:  # (unless its zygote was replaced meanwhile)
            if following and ahead and self._zygotes.get(following[1]) is ahead:
                self._forked = self._own_spawner().submit(self._fork_ahead, ahead, following[0])
        return worker

    @staticmethod
    def _fork_ahead(pending: Future[Zygote], limits: Limits | None) -> tuple[Zygote, Worker] | None:
        try:
            zygote = pending.result()
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
            zygotes, self._zygotes = self._zygotes, {}
        for scipy, zygote in zygotes.items():
            if zygote is None:
                continue
            with contextlib.suppress(SandboxError):
                if self.reuse:
                    _keep(zygote.result(), (self.require_isolation, scipy))
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
