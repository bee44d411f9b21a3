"""Names a generated identifier must not take (IEC 61131-3, 3rd edition), upper case.

Keywords, elementary type names, standard functions and standard function blocks: a step,
variable or block called ``MOVE`` or ``TON`` would shadow or clash with them. MatIEC's
standard library (its ``lib/*.txt``) adds the typed variants of the functions (``ADD_INT``,
``INT_TO_REAL``, ``MUX_DINT_BOOL``…), a few blocks of its own (``PID``, ``RAMP``…) and, for
names of the unit (blocks, types, globals) alone, the variables of its blocks: with the
forward references that Beremiz's build enables (``iec2c -p``), a block named ``Release``
turns the input ``RELEASE`` of ``SEMA`` into a type name. The tests check this module against
the library of the MatIEC in use.
"""

import re

KEYWORDS = frozenset(
    """
    ACTION END_ACTION ARRAY OF AT CASE ELSE END_CASE CONFIGURATION END_CONFIGURATION CONSTANT
    EN ENO EXIT FALSE F_EDGE R_EDGE FOR TO BY DO END_FOR FUNCTION END_FUNCTION FUNCTION_BLOCK
    END_FUNCTION_BLOCK IF THEN ELSIF END_IF INITIAL_STEP END_STEP NOT AND OR XOR MOD PROGRAM
    WITH END_PROGRAM READ_ONLY READ_WRITE REPEAT UNTIL END_REPEAT RESOURCE ON END_RESOURCE
    RETAIN NON_RETAIN RETURN STEP STRUCT END_STRUCT TASK TRANSITION FROM END_TRANSITION TRUE
    TYPE END_TYPE VAR END_VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_TEMP VAR_EXTERNAL VAR_ACCESS
    VAR_CONFIG VAR_GLOBAL WHILE END_WHILE PRIORITY SINGLE INTERVAL CLASS END_CLASS INTERFACE
    END_INTERFACE METHOD END_METHOD PROPERTY END_PROPERTY NAMESPACE END_NAMESPACE USING
    EXTENDS IMPLEMENTS ABSTRACT FINAL OVERRIDE PUBLIC PRIVATE PROTECTED INTERNAL THIS SUPER
    REF REF_TO NULL CONTINUE OVERLAP REFERENCE
    N R S L D P P0 P1 SD DS SL Q T
    """.split()  # noqa: SIM905
)

TYPES = frozenset(
    """
    BOOL SINT INT DINT LINT USINT UINT UDINT ULINT REAL LREAL TIME LTIME DATE LDATE
    TIME_OF_DAY TOD LTIME_OF_DAY LTOD DATE_AND_TIME DT LDATE_AND_TIME LDT STRING WSTRING CHAR
    WCHAR BYTE WORD DWORD LWORD ANY ANY_DERIVED ANY_ELEMENTARY ANY_MAGNITUDE ANY_NUM ANY_REAL
    ANY_INT ANY_UNSIGNED ANY_SIGNED ANY_DURATION ANY_BIT ANY_CHARS ANY_STRING ANY_CHAR
    ANY_DATE
    """.split()  # noqa: SIM905
)

FUNCTIONS = frozenset(
    """
    ABS SQRT LN LOG EXP SIN COS TAN ASIN ACOS ATAN ATAN2 ADD MUL SUB DIV MOD EXPT MOVE
    SHL SHR ROR ROL AND OR XOR NOT SEL MAX MIN LIMIT MUX GT GE EQ LE LT NE LEN LEFT RIGHT
    MID CONCAT INSERT DELETE REPLACE FIND TRUNC ROUND ADD_TIME SUB_TIME MUL_TIME DIV_TIME
    CONCAT_DATE_TOD CONCAT_DT CONCAT_DATE CONCAT_TOD SPLIT_DATE SPLIT_TOD SPLIT_DT
    DAY_OF_WEEK TO_BCD FROM_BCD BCD_TO_INT INT_TO_BCD REAL_TO_INT INT_TO_REAL DINT_TO_REAL
    REAL_TO_DINT TIME_TO_REAL REAL_TO_TIME BOOL_TO_INT INT_TO_BOOL TO_INT TO_REAL TO_DINT
    TO_BOOL TO_TIME TO_STRING
    """.split()  # noqa: SIM905
)

FUNCTION_BLOCKS = frozenset(
    """
    SR RS SEMA R_TRIG F_TRIG CTU CTD CTUD CTU_INT CTU_DINT CTU_LINT CTU_UDINT CTU_ULINT
    CTD_INT CTD_DINT CTD_LINT CTD_UDINT CTD_ULINT CTUD_INT CTUD_DINT CTUD_LINT CTUD_UDINT CTUD_ULINT
    TP TON TOF TONR TP_LTIME TON_LTIME TOF_LTIME RTC
    """.split()  # noqa: SIM905
)

MATIEC_BLOCKS = frozenset("DERIVATIVE HYSTERESIS INTEGRAL PID RAMP DIVTIME MULTIME".split())  # noqa: SIM905

MATIEC_VARIABLES = frozenset(
    """
    AUTO BUSY CD CDT CD_T CLAIM CLK CU CURRENT_TIME CU_T CV CYCLE DTERM EPS ERROR ET G IN IN0
    IN1 IN2 ITERM K KP LD M MN MX OFFSET PDT PREV_IN PT PV Q1 QD QU Q_INTERNAL R1 RELEASE RUN
    S1 SP START_TIME STATE TD TR X0 X1 X2 X3 XI XIN XIN1 XIN2 XOUT
    """.split()  # noqa: SIM905
)
"""The variables of MatIEC's library blocks: forbidden as unit names only."""

_TYPE = "(?:" + "|".join(sorted(TYPES, key=len, reverse=True)) + ")"
_TYPED = "(?:" + "|".join(sorted(FUNCTIONS | MATIEC_BLOCKS, key=len, reverse=True)) + ")"
TYPED_FUNCTION = re.compile(
    rf"{_TYPE}_(?:BCD_)?TO_(?:BCD_)?{_TYPE}|{_TYPE}_TO_BCD|BCD_TO_{_TYPE}"
    rf"|{_TYPED}_{_TYPE}(?:_{_TYPE})?"
)
"""The typed variants of the standard functions in MatIEC's library (``INT_TO_REAL``…)."""

RESERVED = KEYWORDS | TYPES | FUNCTIONS | FUNCTION_BLOCKS | MATIEC_BLOCKS


def is_reserved(name: str) -> bool:
    upper = name.upper()
    return upper in RESERVED or TYPED_FUNCTION.fullmatch(upper) is not None


def is_reserved_for_unit(name: str) -> bool:
    """Reserved as the name of a block, type or global, where MatIEC's block variables count."""
    return is_reserved(name) or name.upper() in MATIEC_VARIABLES
