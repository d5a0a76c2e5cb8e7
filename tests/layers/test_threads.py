"""No shared mutable state across threads (issue 37, class 8): threads asking for the runtime
modules at once leave no top-level runtime module registered (a generated Python target then
imports its own copy, not the package's), and threads using the API at once get each its own
answer and its own record of what it read."""

import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"

LOADERS = textwrap.dedent("""
    import sys, threading
    from swarmvm.compiler import runtime_files as r
    start = threading.Barrier(4)
    def load(f):
        start.wait()
        f()
    threads = [threading.Thread(target=load, args=(f,))
               for f in (r.python_app, r.reference_vm, r.learning, r.python_vm)]
    for t in threads: t.start()
    for t in threads: t.join()
    print(sorted(m for m in ("swarmvm_vm", "swarmvm_format", "swarmvm_step_source", "swarmvm_app") if m in sys.modules))
""")


def test_runtime_modules_loaded_by_threads_at_once_register_no_top_level_module():
    for _ in range(20):            # fresh processes: the race is in the first load
        result = subprocess.run([sys.executable, "-c", LOADERS], capture_output=True, text=True, timeout=60, cwd=ROOT)
        assert result.returncode == 0, result.stderr
        assert result.stdout == "[]\n"


def test_threads_using_the_api_at_once_each_get_their_own_answer(tmp_path):
    code = textwrap.dedent("""
        import sys, threading
        from swarmvm import api
        example, out = sys.argv[1], sys.argv[2]
        results, errors = {}, []
        def work(k):
            try:
                results[k] = len(api.write_image([example], "%s/%d.svm" % (out, k)).packed_image)
                api.check([example])
            except Exception as exc:      # noqa: BLE001  (reported below)
                errors.append(repr(exc))
        threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
        for t in threads: t.start()
        for t in threads: t.join()
        print(len(errors), len(results), errors)
    """)
    result = subprocess.run([sys.executable, "-c", code, str(EXAMPLE), str(tmp_path)], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert result.stdout == "0 8 []\n"
    images = [p.read_bytes() for p in tmp_path.glob("*.svm")]
    assert len(images) == 8 and len(set(images)) == 1
