<?xml version="1.0" encoding="UTF-8"?>
<core:CityModel xmlns:core="http://www.opengis.net/citygml/2.0" xmlns:veg="http://www.opengis.net/citygml/vegetation/2.0" xmlns:gml="http://www.opengis.net/gml">
  <core:cityObjectMember>
    <veg:SolitaryVegetationObject gml:id="tree1"/>
  </core:cityObjectMember>
</core:CityModel>
