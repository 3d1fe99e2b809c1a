"""``python -m services.cli`` is ``skydeck``."""

from services.cli.main import main

raise SystemExit(main())
