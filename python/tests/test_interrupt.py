"""Ctrl-C during a long simulation: KeyboardInterrupt as soon as the library stops, as SIGINT
stops the command; the next run is not affected."""
import os
import subprocess
import sys
import textwrap

from conftest import SOURCE

SCRIPT = textwrap.dedent("""
    import os, signal, sys, threading, time
    import shpb
    scene = shpb.Scene.load(sys.argv[1])
    scene.duration_s = 0.05  # sixty times the test's own duration: seconds of solving
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    try:
        shpb.simulate(scene)
        print("not interrupted")
    except KeyboardInterrupt:
        print("interrupted after %.1f s" % (time.monotonic() - start))
    run = shpb.simulate(sys.argv[1])
    print("next run stable:", run.stable)
""")


# Each script runs the classic experiment in a Python of its own and ends within seconds; a minute
# means a run was not stopped, or never started.
HANG_S = 60


def run_script(script):
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    p = subprocess.run([sys.executable, "-c", script, str(scene)], capture_output=True, text=True,
                       timeout=HANG_S, env=os.environ)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_sigint_interrupts_a_simulation_and_the_next_run_is_clean():
    # The solve stops within a poll of the library's loop.
    lines = run_script(SCRIPT).splitlines()
    assert lines[0].startswith("interrupted after"), lines
    assert lines[1] == "next run stable: True"


FORK_SCRIPT = textwrap.dedent("""
    import multiprocessing, sys
    import shpb
    scene = shpb.Scene.load(sys.argv[1])
    shpb.simulate(scene)  # the parent has run before forking (a kept worker thread would exist)
    def run(velocity):
        scene.striker.velocity_m_s = velocity
        return shpb.simulate(scene).stable
    with multiprocessing.get_context("fork").Pool(2) as pool:
        print("forked children stable:", pool.map(run, [10.0, 12.0]))
""")


def test_a_forked_child_runs_simulations_from_its_main_thread():
    # A child forked by multiprocessing has none of its parent's threads: work handed to a worker
    # thread the parent started would wait for ever.
    assert run_script(FORK_SCRIPT).strip() == "forked children stable: [True, True]"


OWN_HANDLER_SCRIPT = textwrap.dedent("""
    import os, signal, sys, threading
    import shpb
    scene = shpb.Scene.load(sys.argv[1])
    scene.duration_s = 0.004  # five times the test's own: seconds of solving, past the signal
    received = []
    signal.signal(signal.SIGINT, lambda number, frame: received.append(number))
    threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    run = shpb.simulate(scene)
    print("run stable:", run.stable, "handler called:", received == [signal.SIGINT])
""")


def test_a_sigint_handler_of_the_users_own_runs_and_the_simulation_completes():
    # Only Python's default handler means "stop": a handler the user installed decides for itself,
    # as it does around any other call, and is called once the work returns.
    assert run_script(OWN_HANDLER_SCRIPT).strip() == "run stable: True handler called: True"


MONTE_CARLO_SCRIPT = textwrap.dedent("""
    import os, pathlib, signal, sys, threading, time
    import shpb
    lanl = pathlib.Path(sys.argv[1]).parents[1] / "lanl-cu-ofe-273k" / "scene.json"
    sent = []
    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer(0.5, interrupt).start()
    try:
        shpb.process(lanl, draws=300000)  # minutes of draws
        print("not interrupted")
    except KeyboardInterrupt:
        print("stopped after %.3f s" % (time.monotonic() - sent[0]))
    print("next run draws:", shpb.process(lanl, draws=20).summary["uncertainty"]["draws"])
""")

# A draw of the LANL copper's uncertainty is reduced in milliseconds; a stop within a few seconds
# leaves a loaded machine its margin, and is far from the minutes the whole Monte Carlo takes.
STOP_WITHIN_S = 5.0


def test_sigint_stops_the_monte_carlo_of_a_measurement_uncertainty():
    lines = run_script(MONTE_CARLO_SCRIPT).splitlines()
    assert lines[0].startswith("stopped after"), lines
    assert float(lines[0].split()[2]) < STOP_WITHIN_S, lines
    assert lines[1] == "next run draws: 20"


PLAN_SCRIPT = textwrap.dedent("""
    import os, signal, sys, threading, time
    import shpb
    # The plan-al6061 search at its default tolerances: minutes of simulations.
    scene = os.path.join(os.path.dirname(os.path.dirname(sys.argv[1])), "plan-al6061", "scene.json")
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    try:
        shpb.plan(scene, rate=2500)
        print("not interrupted")
    except KeyboardInterrupt:
        print("interrupted after %.1f s" % (time.monotonic() - start))
""")


def test_sigint_stops_a_plan_search():
    # The search's runs poll the library's flag as the command's poll SIGINT.
    assert run_script(PLAN_SCRIPT).startswith("interrupted after")
