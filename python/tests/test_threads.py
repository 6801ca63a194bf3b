"""One Solver, Wheelset or FlexibilityTable shared by several threads (docs/PYTHON.md "Threads"):
each call holds the object's lock, so the interpreter never crashes and every result equals the
one of the same call on one thread. Without the lock a Wheelset shared by two threads corrupted
the heap (a segmentation fault) and a shared Solver gave "no contact patch is set"."""
import threading

import numpy as np
import pytest

import railcontact

COARSE = 1.0e-3  # m: wheelset elements, coarse for speed
THREADS = 4


def hammer(work, threads=THREADS):
    """Runs work(index) on `threads` threads at once; returns their results (or raises the first
    exception a thread raised)."""
    results, errors = [None] * threads, []
    start = threading.Barrier(threads)

    def run(index):
        try:
            start.wait()
            results[index] = work(index)
        except BaseException as e:  # noqa: B902 - handed to the main thread
            errors.append(e)

    pool = [threading.Thread(target=run, args=(k,)) for k in range(threads)]
    for t in pool:
        t.start()
    for t in pool:
        t.join()
    if errors:
        raise errors[0]
    return results


def test_one_solver_on_several_threads_equals_one_thread():
    solver = railcontact.Solver("nh-fastsim", elements=3000)
    solver.set_ellipse(6e-3, 4e-3, 80e3)
    creepages = [(1e-4 * k, -5e-5 * k, 0.02 * k) for k in range(12)]
    # nh-fastsim's solve starts from nothing of the previous one: the same call gives the same
    # bits whichever thread makes it.
    serial = [solver.solve(*c, tractions=True) for c in creepages]

    def work(index):
        out = []
        for _ in range(3):
            for k in range(len(creepages)):
                c = creepages[(k + index) % len(creepages)]
                out.append((c, solver.solve(*c, tractions=(k % 2 == 0))))
        return out

    for out in hammer(work):
        for c, r in out:
            ref = serial[creepages.index(c)]
            assert (r.F1_N, r.F2_N, r.M3_Nm, r.adhesion_fraction) == (ref.F1_N, ref.F2_N, ref.M3_Nm,
                                                                        ref.adhesion_fraction)
            assert r.normal == ref.normal
            if r.tractions is not None:
                np.testing.assert_array_equal(r.tractions.p1_Pa, ref.tractions.p1_Pa)


def test_one_solver_set_and_solved_on_several_threads():
    """Threads setting different patches and solving on one Solver: each solve is on some patch
    set by a thread, and its result carries that patch's normal results (the same call)."""
    solver = railcontact.Solver("nh-fastsim", elements=1500)
    patches = [(6e-3, 4e-3, 80e3), (5e-3, 5e-3, 60e3), (4e-3, 7e-3, 90e3), (7e-3, 3e-3, 70e3)]
    reference = {}
    for p in patches:
        solver.set_ellipse(*p)
        reference[solver.normal.normal_force_N] = solver.solve(1e-3, 5e-4, 0.1)

    def work(index):
        for _ in range(30):
            solver.set_ellipse(*patches[index])
            r = solver.solve(1e-3, 5e-4, 0.1)
            ref = reference[r.normal.normal_force_N]  # the patch the forces were computed on
            assert (r.F1_N, r.F2_N, r.M3_Nm) == (ref.F1_N, ref.F2_N, ref.M3_Nm)
            assert r.normal == ref.normal
        return True

    assert all(hammer(work))


def test_a_solver_reconfigured_while_another_thread_solves():
    """configure() on one thread, solve() on others: a solve either finds the patch (the numbers
    of the one-thread solve) or raises InvalidInputError "no contact patch is set" after a change
    of mesh discarded it; never a crash or another error."""
    solver = railcontact.Solver("nh-fastsim", elements=3000)
    solver.set_ellipse(6e-3, 4e-3, 80e3)
    ref = solver.solve(1e-3)
    outcomes = {"solved": 0, "no patch": 0}
    lock = threading.Lock()

    def work(index):
        for k in range(30):
            if index == 0:
                solver.configure(mu=0.3)  # friction alone keeps the patch
                if k % 3 == 2:
                    solver.configure(elements=3000 + k)  # a new mesh discards it: set it again
                    solver.configure(elements=3000)
                    solver.set_ellipse(6e-3, 4e-3, 80e3)
            else:
                try:
                    r = solver.solve(1e-3)
                    assert r.F1_N == ref.F1_N
                    key = "solved"
                except railcontact.InvalidInputError as e:
                    assert "no contact patch is set" in str(e)
                    key = "no patch"
                with lock:
                    outcomes[key] += 1
        return True

    assert all(hammer(work))
    assert outcomes["solved"] > 0


def test_one_wheelset_on_several_threads_equals_one_thread():
    wheelset = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    ys = [k * 1e-3 for k in range(-3, 4)]
    # warm_start=False: every evaluation starts cold, the same call gives the same bits.
    serial = {y: wheelset.evaluate(y=y, yaw=1e-3).force_track_N for y in ys}

    def work(index):
        out = []
        for k in range(len(ys)):
            y = ys[(k + index) % len(ys)]
            out.append((y, wheelset.evaluate(y=y, yaw=1e-3).force_track_N))
        out.append((None, wheelset.options))
        return out

    for out in hammer(work):
        for y, force in out:
            if y is not None:
                np.testing.assert_array_equal(force, serial[y])


def test_one_wheelset_with_warm_start_on_several_threads():
    """With warm_start each evaluation starts from the previous one's pressures, heights and
    vertical balance, whichever thread made it: the forces agree with the one-thread ones to the
    vertical balance's tolerance (1e-5 of the load: a different start converges to the same
    solution)."""
    wheelset = railcontact.Wheelset(element_size=COARSE)
    ys = [k * 1e-3 for k in range(-3, 4)]
    cold = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    serial = {y: cold.evaluate(y=y).force_track_N for y in ys}

    def work(index):
        return [(y, wheelset.evaluate(y=y).force_track_N) for y in ys[index % 2::2]]

    for out in hammer(work):
        for y, force in out:
            np.testing.assert_allclose(force, serial[y], rtol=0, atol=1e-5 * 98.1e3 * 2)


def test_a_wheelset_batch_and_evaluations_share_one_wheelset():
    wheelset = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    states = np.array([[y, 0.0, 0.0, 1e-3] for y in (-2e-3, 0.0, 2e-3)])
    serial = [r.force_track_N for r in wheelset.batch(states, threads=1)]

    def work(index):
        if index % 2 == 0:
            return [r.force_track_N for r in wheelset.batch(states, threads=2)]
        return [wheelset.evaluate(*row).force_track_N for row in states]

    for out in hammer(work):
        for force, ref in zip(out, serial):
            np.testing.assert_array_equal(force, ref)


def test_an_object_dropped_by_one_thread_while_another_uses_it():
    """A thread drops its reference while another solves: the object lives on until the last
    call returns (Python holds it for the call)."""
    for _ in range(3):
        holder = {"solver": railcontact.Solver(elements=500), "wheelset": railcontact.Wheelset(element_size=COARSE)}
        holder["solver"].set_ellipse(6e-3, 4e-3, 80e3)
        solver, wheelset = holder["solver"], holder["wheelset"]
        started = threading.Event()

        def use(solver=solver, wheelset=wheelset):
            started.set()
            return solver.solve(1e-3).F1_N, wheelset.evaluate(y=1e-3).force_track_N[1]

        result = []
        t = threading.Thread(target=lambda: result.append(use()))
        del solver, wheelset
        t.start()
        started.wait()
        holder.clear()  # the last references but the running call's
        t.join()
        assert result and result[0][0] < 0


def test_a_progress_callback_cannot_use_the_object_it_reports_on():
    """A progress callback runs inside the build, which holds the wheelset's lock: a call on the
    same wheelset from it raises InvalidInputError (not a deadlock), and the build stops with it."""
    wheelset = railcontact.Wheelset(element_size=COARSE)

    def progress(done, total):
        wheelset.evaluate_table(0.0)

    with pytest.raises(railcontact.InvalidInputError, match="busy"):
        wheelset.build_table([-1e-3, 0.0, 1e-3], (0.0,), (98.1e3,), progress=progress)


def test_a_flexibility_table_read_by_solvers_on_several_threads():
    table = railcontact.FlexibilityTable.build([-2e-3, 0.0, 2e-3], [80e3, 100e3], elements=300)
    solvers = [railcontact.Solver(elements=300) for _ in range(THREADS)]
    ref = railcontact.Solver(elements=300)
    ref.set_flextable_patch(table, 1e-3, 90e3)
    expected = ref.solve(1e-3)

    def work(index):
        out = []
        for _ in range(5):
            solvers[index].set_flextable_patch(table, 1e-3, 90e3)
            out.append(solvers[index].solve(1e-3).F1_N)
            out.append(table.lookup(1e-3, 90e3).f11_N)
        return out

    for out in hammer(work):
        assert out[0::2] == [expected.F1_N] * 5
