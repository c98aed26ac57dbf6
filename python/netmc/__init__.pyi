# Type stubs of the netmc package for editors. The keywords of sim() and sweep() are the flags of
# `netmc sim` and `netmc sweep` (help(netmc.sim) lists them); tests/python checks that every flag
# the CLI registers is here.
from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy
import pandas

__version__: str

_Value = Union[str, int, float, PathLike[str]]
_Values = Union[_Value, Sequence[_Value]]

class Study:
    text: str
    results: Dict[str, Any]
    labels: List[str]
    def to_json(self) -> str: ...
    @property
    def table(self) -> pandas.DataFrame: ...
    @property
    def iterations(self) -> pandas.DataFrame: ...
    def trace(self, label: str, iteration: Optional[int] = ...) -> Dict[str, numpy.ndarray]: ...

def set_log_level(level: str) -> None: ...
