"""The machine line of every benchmark page: the CPU's model and cores
(docs/benchmarks.md names the machine of each section)."""
import os


def machine():
    """(CPU model name, logical cores)."""
    model = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return model, os.cpu_count()


def cpu_model():
    return machine()[0]
