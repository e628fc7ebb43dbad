"""Progress of work made of a few unequal stages, as a tqdm bar on stderr that names the stage
under way (the command line shows it when stderr is a terminal and --no-progress is not given).
Work counted in equal units (steps, samples, points) keeps a plain tqdm bar of them."""
from __future__ import annotations

from contextlib import contextmanager
from typing import Callable, Iterator

from tqdm import tqdm


@contextmanager
def stages(desc: str, total: int, enabled: bool) -> Iterator[Callable[[str], None]]:
    """A bar over ``total`` stages titled ``desc``; yields ``begin(name)``, which counts the
    stage under way as done and shows ``name`` as the next. Leaving the block counts the last
    stage done; an exception leaves the bar where the work stopped."""
    bar = tqdm(total=total, desc=desc, disable=not enabled, mininterval=0,
               bar_format="{desc} |{bar}| {n}/{total} stages done [{elapsed}]")
    started = []

    def begin(name: str) -> None:
        bar.set_description_str(f"{desc}: {name}", refresh=not started)
        if started:
            bar.update()
        started.append(name)

    with bar:
        yield begin
        bar.update(bar.total - bar.n)
