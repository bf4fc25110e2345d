"""A xacro file cannot be expanded.

## What it does
Expands `*.xacro` files in-process with the `xacro` package (no ROS needed) and
reports the first error xacro meets: an undefined property or macro, a missing
or unreadable include, an XML error in an included file, a `$(find pkg)` whose
package is not found, a `$(arg name)` with no value, runaway recursion. The
message is xacro's, naming the file and line where the problem is when it can
be found; the finding's line is in the file you checked (for an error inside an
included file, the line of the `<xacro:include>` that leads to it).

When an argument is the cause, the message names it. If an include, `$(find)`,
`$(arg)` or `${}` fails because an argument is empty or has no value, the message
gives the entry file being expanded and where the argument's default is declared
(`file:line`). It also lists the macro parameters, properties and argument defaults
the value passed through, and the `--xacro-arg NAME:=VALUE` to pass (with the values
that name an existing file when the include's path is built from the argument). If a
file or package is missing inside an `<xacro:if>` or `<xacro:unless>` that depends
on an argument, the message names that argument and the value that skips the block.

## Why is this bad?
`xacro` (and so `ros2 launch`, `robot_state_publisher`, Gazebo's spawn scripts)
stops at the same error: no URDF is produced and nothing downstream can load the
robot. Since there is no expanded document, no other rule can check the robot.

## How to fix
Fix the cause named in the message: define the property before it is used,
correct the include path, close the tag in the included file. For
`$(find pkg)`, tell urdflint where the package is with `--package-path pkg=DIR`
(or `package-paths` in the configuration, or `ROS_PACKAGE_PATH`); a
`package.xml` in a folder above the file is found on its own. Give xacro
arguments with `--xacro-arg name:=value`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "X010",
    "xacro-expansion-failed",
    Severity.ERROR,
    requires_robot=False,
    fix="Fix the xacro error named in the message; check the result with `xacro FILE`.",
)
def check(doc: Document) -> Iterator[Hit]:
    problem = doc.problem
    if problem is not None and problem.code == "X010":
        line, column = problem.line, problem.column
        yield Hit(None, problem.message, line=line, column=column, path=problem.path)
