( SYNTAX TEST "source.fanuc-macro" "functions, operators, brackets"
#1=SIN[#2]+COS[#3]-TAN[#4]
(  ^^^ support.function.math.fanuc-macro
(         ^ keyword.operator.arithmetic.fanuc-macro
(          ^^^ support.function.math.fanuc-macro
(                 ^ keyword.operator.arithmetic.fanuc-macro
(                  ^^^ support.function.math.fanuc-macro
#1=ASIN[#2]*ACOS[#3]/ATAN[#4]/[#5]
(  ^^^^ support.function.math.fanuc-macro
(          ^ keyword.operator.arithmetic.fanuc-macro
(           ^^^^ support.function.math.fanuc-macro
(                   ^ keyword.operator.arithmetic.fanuc-macro
(                    ^^^^ support.function.math.fanuc-macro
#1=ATAN[#2,#3]
(  ^^^^ support.function.math.fanuc-macro
(         ^ punctuation.separator.comma.fanuc-macro
#1=SQRT[ABS[#2]]+ROUND[#3]+FIX[#4]+FUP[#5]
(  ^^^^ support.function.math.fanuc-macro
(       ^^^ support.function.math.fanuc-macro
(                ^^^^^ support.function.math.fanuc-macro - keyword.operator.logical.fanuc-macro
(                          ^^^ support.function.math.fanuc-macro
(                                  ^^^ support.function.math.fanuc-macro
#1=LN[#2]+EXP[#3]+POW[#4,2]+ADP[#5]
(  ^^ support.function.math.fanuc-macro
(         ^^^ support.function.math.fanuc-macro
(                 ^^^ support.function.math.fanuc-macro
(                           ^^^ support.function.math.fanuc-macro
#1=BIN[#2]+BCD[#3]
(  ^^^ support.function.math.fanuc-macro
(          ^^^ support.function.math.fanuc-macro
#1=round[#2]
(  ^^^^^ support.function.math.fanuc-macro
IF[#1EQ1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[#1NE1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[#1GT1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[#1LT1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[#1GE1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[#1LE1]GOTO1
(    ^^ keyword.operator.comparison.fanuc-macro
IF[[#1GT0]AND[#2LT0]]GOTO5
(         ^^^ keyword.operator.logical.fanuc-macro
IF[[#1GT0]OR[#2LT0]]GOTO5
(         ^^ keyword.operator.logical.fanuc-macro
#3=#1XOR#2
(    ^^^ keyword.operator.logical.fanuc-macro
#3=#1AND#2
(    ^^^ keyword.operator.logical.fanuc-macro
#3=#1MOD#2
(    ^^^ keyword.operator.arithmetic.fanuc-macro - support.type.mcode.fanuc-macro
#3=[#1+#2]*[#1-#2]/2
( ^ keyword.operator.assignment.fanuc-macro
(  ^ punctuation.section.brackets.begin.fanuc-macro
(     ^ keyword.operator.arithmetic.fanuc-macro
(        ^ punctuation.section.brackets.end.fanuc-macro
(         ^ keyword.operator.arithmetic.fanuc-macro
(             ^ keyword.operator.arithmetic.fanuc-macro
(                 ^ keyword.operator.arithmetic.fanuc-macro
(                  ^ constant.numeric.fanuc-macro
#1=-1.5+.5
(  ^ keyword.operator.arithmetic.fanuc-macro
(   ^^^ constant.numeric.fanuc-macro
(    ^^ constant.numeric.fanuc-macro
