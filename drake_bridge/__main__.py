"""Entry point: `python -m drake_bridge` runs the JSON-lines server on stdio."""

from drake_bridge.server import main

if __name__ == "__main__":
    raise SystemExit(main())
