( SYNTAX TEST "source.fanuc-macro" "G codes, calls, M codes, addresses, DPRNT"
G90G1G#8X#601
(<--- keyword.other.gcode.fanuc-macro
(  ^^ keyword.other.gcode.fanuc-macro
(    ^ keyword.other.gcode.fanuc-macro
(     ^^ variable.parameter.local.fanuc-macro
(       ^ entity.other.attribute-name.address.fanuc-macro
(        ^^^^ variable.other.common.fanuc-macro
G00 G40 G97 S800 M03
(<--- keyword.other.gcode.fanuc-macro
(       ^^^ keyword.other.gcode.fanuc-macro
(           ^ entity.other.attribute-name.address.fanuc-macro
(            ^^^ constant.numeric.fanuc-macro
(                ^^^ support.type.mcode.fanuc-macro
G92 X49.816 W-60. F3.
(<--- keyword.other.gcode.fanuc-macro
(   ^ entity.other.attribute-name.address.fanuc-macro
(    ^^^^^^ constant.numeric.fanuc-macro
(           ^ entity.other.attribute-name.address.fanuc-macro
(            ^^^^ constant.numeric.fanuc-macro
(                 ^ entity.other.attribute-name.address.fanuc-macro
(                  ^^ constant.numeric.fanuc-macro
G76 P010060 Q100 R0.05
(<--- keyword.other.gcode.fanuc-macro
(   ^ entity.other.attribute-name.address.fanuc-macro
(    ^^^^^^ constant.numeric.fanuc-macro
G01 X51.0,A-45.0 ,R2.
(<--- keyword.other.gcode.fanuc-macro
(        ^ punctuation.separator.comma.fanuc-macro
(         ^ entity.other.attribute-name.address.fanuc-macro
(          ^^^^^ constant.numeric.fanuc-macro
(                ^ punctuation.separator.comma.fanuc-macro
(                 ^ entity.other.attribute-name.address.fanuc-macro
G12.1
(<----- keyword.other.gcode.fanuc-macro
G65P9010A1.B2.
(<--- keyword.control.call.fanuc-macro - keyword.other.gcode.fanuc-macro
(  ^ entity.other.attribute-name.address.fanuc-macro
(   ^^^^ constant.numeric.fanuc-macro
(       ^ entity.other.attribute-name.address.fanuc-macro
(          ^ entity.other.attribute-name.address.fanuc-macro
G66 P9011 Z-10.
(<--- keyword.control.call.fanuc-macro
G66.1 P9012
(<----- keyword.control.call.fanuc-macro
G67
(<--- keyword.control.call.fanuc-macro
g065 p9010
(<---- keyword.control.call.fanuc-macro
G650
(<---- keyword.other.gcode.fanuc-macro - keyword.control.call.fanuc-macro
M98 P0013331
(<--- keyword.control.call.fanuc-macro - support.type.mcode.fanuc-macro
(   ^ entity.other.attribute-name.address.fanuc-macro
(    ^^^^^^^ constant.numeric.fanuc-macro
M98P0013330
(<--- keyword.control.call.fanuc-macro
(   ^^^^^^^ constant.numeric.fanuc-macro
M99
(<--- keyword.control.call.fanuc-macro
M99P20
(<--- keyword.control.call.fanuc-macro
(  ^ entity.other.attribute-name.address.fanuc-macro
M198 P1234
(<---- keyword.control.call.fanuc-macro
M98 <SUB_A>
(<--- keyword.control.call.fanuc-macro
(    ^^^^^ entity.name.function.program.fanuc-macro
M30
(<--- support.type.mcode.fanuc-macro
M#1
(<- support.type.mcode.fanuc-macro
(^^ variable.parameter.local.fanuc-macro
T0101
(<- entity.other.attribute-name.address.fanuc-macro
(^^^^ constant.numeric.fanuc-macro
X-#1 Z[#2*2]
(<- entity.other.attribute-name.address.fanuc-macro
(^ keyword.operator.arithmetic.fanuc-macro
(    ^ entity.other.attribute-name.address.fanuc-macro
(     ^ punctuation.section.brackets.begin.fanuc-macro
x1.5z-2.
(<- entity.other.attribute-name.address.fanuc-macro
(^^^ constant.numeric.fanuc-macro
(   ^ entity.other.attribute-name.address.fanuc-macro
(    ^^^ constant.numeric.fanuc-macro
POPEN
(<----- support.function.io.fanuc-macro
DPRNT[X#100[53]**Z#101[53]]
(<----- support.function.io.fanuc-macro
(    ^ punctuation.section.brackets.begin.fanuc-macro
(     ^ meta.print-arguments.fanuc-macro string.unquoted.print.fanuc-macro
(      ^^^^ meta.print-arguments.fanuc-macro variable.other.print.fanuc-macro
(           ^^ constant.numeric.format.fanuc-macro
(              ^^^ string.unquoted.print.fanuc-macro
(                 ^^^^ variable.other.print.fanuc-macro
(                         ^ punctuation.section.brackets.end.fanuc-macro - meta.print-arguments.fanuc-macro
BPRNT[C**X#5041[3]]
(<----- support.function.io.fanuc-macro
(     ^^^^ string.unquoted.print.fanuc-macro
(         ^^^^^ variable.other.print.fanuc-macro
PCLOS
(<----- support.function.io.fanuc-macro
#1=PRM[1422]
(  ^^^ support.function.system.fanuc-macro
