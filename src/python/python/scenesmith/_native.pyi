"""Type stubs of the Rust extension module `scenesmith._native` (see src/python/lib.rs)."""

class ScenesmithError(Exception):
    """A scenesmith operation failed; the message is the CLI's."""

class PromptError(ScenesmithError):
    """The prompt was refused (empty, not words, or nothing the reader understands)."""

def generate(prompt: str, out: str, seed: int = 0, render: bool = True, stb: bool = True,
             drake_check: bool = True, exports: str = "all", lenient: bool = False,
             resume: bool = False) -> str:
    """Generates a scene; returns the run's summary as JSON text."""

def evaluate(dir: str, stb: bool = True) -> str:
    """Writes metrics.json of the scene in `dir`; returns it as JSON text."""

def export(dir: str, formats: str = "all") -> str:
    """Writes the scene's exports; returns the written exports as JSON text."""
