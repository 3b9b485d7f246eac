"""Type stubs of the extension module `rocking._rocking` (PyO3)."""

from os import PathLike
from typing import Any, Callable, Iterable, Mapping

__version__: str

class ConfigError(ValueError):
    """Bad input (the CLI's exit 2); the message is the CLI's one-line error."""

    key: str | None
    file: str | None
    line: int | None

class RecordError(ConfigError):
    """A record file that cannot be read: `file` and, where one applies, `line`."""

class RunError(RuntimeError):
    """A run that failed after its input was accepted (the CLI's exit 1)."""

Value = float | int | bool | str | PathLike[str]
#: Samples of a ground motion: accelerations (with `dt`), or (times, accelerations).
Samples = Any

class Scene:
    """A resolved, validated scenario (the CLI's --preset/--config and --set)."""

    def __init__(
        self,
        preset: str | None = None,
        *,
        file: str | PathLike[str] | None = None,
        config: Mapping[str, Value | Mapping[str, Value]] | None = None,
        record_h: Samples | None = None,
        record_v: Samples | None = None,
        dt: float | None = None,
        unit: str | None = None,
        **keys: Value | Mapping[str, Value],
    ) -> None: ...
    @staticmethod
    def defaults(
        config: Mapping[str, Value | Mapping[str, Value]] | None = None, **keys: Value | Mapping[str, Value]
    ) -> Scene: ...
    def with_(
        self,
        config: Mapping[str, Value | Mapping[str, Value]] | None = None,
        *,
        record_h: Samples | None = None,
        record_v: Samples | None = None,
        dt: float | None = None,
        unit: str | None = None,
        **keys: Value | Mapping[str, Value],
    ) -> Scene: ...
    def to_dict(self) -> dict[str, Any]: ...
    def resolved(self) -> dict[str, Any]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def psi_rad(self) -> float: ...
    @property
    def p_per_s(self) -> float: ...
    @property
    def r_m(self) -> float: ...
    def __reduce__(self) -> tuple[Any, tuple[str, str, str, Any]]: ...

def presets() -> list[str]: ...
def _keys_help() -> str: ...
def _undocumented_keys() -> list[str]: ...
def _scene_from_state(text: str, base_dir: str, origin: str, memory: Any = None) -> Scene: ...
def _simulate(scene: Scene) -> dict[str, Any]: ...
def _lyapunov(scene: Scene) -> dict[str, Any]: ...
def _sweep(
    scene: Scene,
    param: str,
    start: float,
    stop: float,
    step: float,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    continuation: str = "none",
    lyapunov: bool = False,
    threads: int | None = None,
    shard: tuple[int, int] | None = None,
    check_only: bool = False,
    progress: Callable[[int, int], Any] | None = None,
) -> dict[str, Any]: ...
def _outcome_map(
    scene: Scene,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    threads: int | None = None,
    full: bool = False,
    coarse: int = 32,
    executor: Callable[[list[int], list[list[tuple[float, float, float]]], Any], Iterable[dict[str, Any]]] | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> dict[str, Any]: ...
def _outcome_cells(
    scene: Scene,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    indices: list[int],
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    threads: int | None = None,
    full: bool = False,
    coarse: int = 32,
    known: list[list[tuple[float, float, float]]] = ...,
    labels: Any = None,
) -> dict[str, Any]: ...
def _fragility_blocks(
    scene: Scene, blocks: list[tuple[float, float]] | None, im: str = "pga"
) -> list[tuple[float, float]]: ...
def _fragility_runs(
    scene: Scene,
    records: list[tuple[str, str | None]],
    levels: list[float],
    blocks: list[tuple[float, float]],
    *,
    im: str = "pga",
    threads: int | None = None,
    indices: list[int] | None = None,
    check_only: bool = False,
    progress: Callable[[int, int], Any] | None = None,
) -> dict[str, Any]: ...
def _fragility_fits(
    blocks: int, levels: list[float], records: int, threshold: float, run: list[int], end: list[str], peak: list[float]
) -> list[dict[str, Any]]: ...
def _spectrum(
    scene: Scene,
    record: str,
    sizes: tuple[float, float, int],
    *,
    unit: str | None = None,
    size: str = "r",
    b_over_h: list[float] | None = None,
    scale: float | None = None,
    pga: float | None = None,
    overturn_scale: bool = False,
    search_step: float = 0.1,
    search_max: float = 5.0,
    rel_tol: float = 1e-3,
    threads: int | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> dict[str, Any]: ...
def _sliding_spectrum(
    scene: Scene,
    record: str,
    mu: list[float],
    *,
    unit: str | None = None,
    block: tuple[float, float] | None = None,
    kinetic_ratio: float = 1.0,
    scale: float | None = None,
    pga: float | None = None,
    threads: int | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> dict[str, Any]: ...
