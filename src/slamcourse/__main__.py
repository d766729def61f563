from slamcourse.cli import main

raise SystemExit(main())
